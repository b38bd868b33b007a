// Each coupling scheme driven against stand-in modules: in-process fakes of the wire interface,
// registered as the built-in (inproc) DEM and fluid, that record every request. The scheme's
// exchange order, its half steps (split_last, the held force riding on the next Advance) and
// whether the modules hold whole steps (the condition for a checkpoint) are checked without the
// real DEM or fluid.
#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <vector>

#include "observers/run_observer.hpp"
#include "run/run_clock.hpp"
#include "run/run_modules.hpp"
#include "run/run_options.hpp"
#include "run/time_plan.hpp"
#include "scene/scene_loader.hpp"
#include "schemes/coupling_scheme.hpp"
#include "wire/inproc_registry.hpp"
#include "wire/module_server.hpp"
#include "wire/protocol.hpp"

namespace rockcut::coupler {
namespace {

constexpr std::uint64_t kParticles = 4;
constexpr double kDt = 1e-6;

// What a stand-in received, one line per request: "advance 3 split apply_first force=4",
// "apply_forces force=4", "fluid_step dt=3e-06 report".
std::mutex log_mutex;
std::vector<std::string> requests;

void note(std::string line) {
  std::lock_guard<std::mutex> lock(log_mutex);
  requests.push_back(std::move(line));
}

std::string force_rows(const wire::Message& m) {
  return m.has_array(wire::field::kForce)
             ? " force=" + std::to_string(m.array(wire::field::kForce, 2).size() / 2)
             : std::string();
}

class StandInDem final : public wire::ModuleHandler {
 public:
  wire::ModuleKind kind() const override { return wire::MODULE_KIND_DEM; }
  std::string name() const override { return "stand-in dem"; }
  std::string version() const override { return "0"; }
  std::vector<std::string> models() const override { return {"dem"}; }
  void handle(const wire::Message& request, wire::Message& reply) override {
    const wire::Envelope& e = request.envelope;
    if (e.has_advance()) {
      const wire::Advance& a = e.advance();
      note("advance " + std::to_string(a.steps()) + (a.split_last() ? " split" : "") +
           (a.apply_forces_first() ? " apply_first" : "") + force_rows(request));
      step_ += a.steps();
      time_s_ += a.steps() * a.dt_s();
      if (a.split_last()) {  // positions at the end, the last step's second half kick pending
        wire::Kinematics* k = reply.envelope.mutable_kinematics();
        k->set_step(step_);
        k->set_time_s(time_s_);
        const std::vector<double> positions(2 * kParticles, 0.5);
        reply.add_array(wire::field::kPosition, positions, 2);
      } else {
        report(reply);
      }
    } else if (e.has_apply_forces()) {
      note("apply_forces" + force_rows(request));
      report(reply);
    } else {
      throw std::runtime_error("stand-in dem: unexpected request");
    }
  }

 private:
  void report(wire::Message& reply) const {
    wire::StepReport* r = reply.envelope.mutable_step_report();
    r->set_step(step_);
    r->set_time_s(time_s_);
    (*r->mutable_scalars())["tool_force_x_n_per_m"] = 1.0;
  }
  std::uint64_t step_ = 0;
  double time_s_ = 0.0;
};

class StandInFluid final : public wire::ModuleHandler {
 public:
  wire::ModuleKind kind() const override { return wire::MODULE_KIND_FLUID; }
  std::string name() const override { return "stand-in fluid"; }
  std::string version() const override { return "0"; }
  std::vector<std::string> models() const override { return {"explicit"}; }
  void handle(const wire::Message& request, wire::Message& reply) override {
    if (!request.envelope.has_fluid_step()) throw std::runtime_error("stand-in fluid: unexpected");
    const wire::FluidStep& s = request.envelope.fluid_step();
    char line[96];
    std::snprintf(line, sizeof line, "fluid_step dt=%g%s positions=%zu", s.dt_s(),
                  s.report() ? " report" : "",
                  request.has_array(wire::field::kPosition)
                      ? request.array(wire::field::kPosition, 2).size() / 2
                      : std::size_t{0});
    note(line);
    reply.envelope.mutable_fluid_result();
    const std::vector<double> forces(2 * kParticles, 1e-3);
    reply.add_array(wire::field::kForce, forces, 2);
  }
};

int serve_dem(zmq::context_t& context, const std::string& endpoint) {
  StandInDem dem;
  return wire::serve(context, endpoint, dem);
}
int serve_fluid(zmq::context_t& context, const std::string& endpoint) {
  StandInFluid fluid;
  return wire::serve(context, endpoint, fluid);
}
// test_coupler links no real module: these are the built-in ones here.
const bool registered = wire::register_inproc_module(wire::MODULE_KIND_DEM, serve_dem) &&
                        wire::register_inproc_module(wire::MODULE_KIND_FLUID, serve_fluid);

// Records every `every`-th step, as the run's recorder would for its rows.
class EveryNthStep final : public ExchangeSchedule {
 public:
  explicit EveryNthStep(std::uint64_t every) : every_(every) {}
  bool completes_step_at(std::uint64_t step, double) const override { return step % every_ == 0; }
  std::uint64_t steps_to_next_record(std::uint64_t step, double) const override {
    return every_ - step % every_;
  }

 private:
  std::uint64_t every_;
};

struct Driven {
  scene::LoadedScene loaded;
  RunOptions options;
  TimePlan plan;
  RunObservers observers;
  std::unique_ptr<RunModules> modules;
  std::unique_ptr<CouplingScheme> scheme;
  RunClock clock;

  Driven(const std::string& scene_file, unsigned interval, std::uint64_t total_steps) {
    EXPECT_TRUE(registered);
    loaded = scene::load_scene(std::string(ROCKCUT_SOURCE_DIR) + "/cases/" + scene_file, {});
    options.transport = Transport::inproc;
    plan.dt_s = kDt;
    plan.coupling_interval = interval;
    plan.total_steps = total_steps;
    modules = std::make_unique<RunModules>(options, loaded);
    modules->start();  // the handshakes; Init is the real modules' business, not the scheme's
    modules->dem().init.set_particle_count(kParticles);
    scheme = make_coupling_scheme(loaded.scene, plan, *modules, observers);
    requests.clear();
  }
};

TEST(CouplingSchemes, HalfStepExchangeOrderHalfStepsAndHeldForces) {
  Driven run("cutting/saturated_reduced.pbtxt", 3, 12);
  EXPECT_STREQ(run.scheme->name(), "half-step exchange");
  const EveryNthStep rows(6);  // a row every 6 steps: every second exchange of N = 3

  run.scheme->initialise(run.clock);
  EXPECT_TRUE(run.scheme->between_steps());
  // t = 0: positions to the fluid (no time step), its force back, then the half kick.
  EXPECT_EQ(requests, (std::vector<std::string>{"advance 0 split", "fluid_step dt=0 report positions=4",
                                                "apply_forces force=4"}));
  EXPECT_EQ(run.clock.step, 0u);

  requests.clear();
  run.scheme->advance(run.clock, 3, rows);  // to step 3: not recorded
  // The fluid's force waits for the next Advance: the DEM is mid-step, no checkpoint now.
  EXPECT_EQ(requests, (std::vector<std::string>{"advance 3 split",
                                                "fluid_step dt=3e-06 positions=4"}));
  EXPECT_FALSE(run.scheme->between_steps());
  EXPECT_EQ(run.clock.step, 3u);

  requests.clear();
  run.scheme->advance(run.clock, 3, rows);  // to step 6: recorded
  // The held force completes step 3 first; step 6 is completed in its own exchange.
  EXPECT_EQ(requests, (std::vector<std::string>{"advance 3 split apply_first force=4",
                                                "fluid_step dt=3e-06 report positions=4",
                                                "apply_forces force=4"}));
  EXPECT_TRUE(run.scheme->between_steps());
  EXPECT_EQ(run.clock.step, 6u);
  EXPECT_NEAR(run.clock.time_s, 6 * kDt, 1e-18);
  EXPECT_EQ(run.clock.exchanges, 3u);
  ASSERT_EQ(run.clock.scalars.size(), 1u);  // the DEM's, taken at the completed step
  EXPECT_EQ(run.clock.scalars[0].first, "tool_force_x_n_per_m");
  EXPECT_EQ(run.scheme->regular_steps(run.clock, rows), 3u);
  EXPECT_FALSE(run.scheme->done(run.clock));
}

TEST(CouplingSchemes, DrySchemeAdvancesToTheNextRecordInOneMessage) {
  Driven run("cutting/dry_reduced.pbtxt", 1, 100);
  const EveryNthStep rows(40);
  EXPECT_EQ(run.scheme->regular_steps(run.clock, rows), 40u);
  run.scheme->advance(run.clock, 40, rows);
  run.scheme->advance(run.clock, 40, rows);
  // Whole steps only: no split, no fluid, a report per message.
  EXPECT_EQ(requests, (std::vector<std::string>{"advance 40", "advance 40"}));
  EXPECT_TRUE(run.scheme->between_steps());
  EXPECT_EQ(run.clock.step, 80u);
  EXPECT_EQ(run.clock.exchanges, 2u);
  EXPECT_EQ(run.scheme->regular_steps(run.clock, rows), 40u);
}

}  // namespace
}  // namespace rockcut::coupler
