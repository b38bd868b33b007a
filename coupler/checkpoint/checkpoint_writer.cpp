#include "checkpoint/checkpoint_writer.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "run/named_values_state.hpp"
#include "run/signals.hpp"
#include "wire/protocol.hpp"

namespace rockcut::coupler {

namespace {
namespace fs = std::filesystem;
using clock_type = std::chrono::steady_clock;

double seconds_since(clock_type::time_point start) {
  return std::chrono::duration<double>(clock_type::now() - start).count();
}
}  // namespace

RunCheckpoints::RunCheckpoints(const RunParts& run)
    : run_(run),
      enabled_(!run.options.no_checkpoints),
      next_time_s_(run.loaded.scene.output().checkpoint_interval_s()) {}

void RunCheckpoints::save(state::StateArchive& a, double wall_s) const {
  const RunClock& c = run_.clock;
  a.put("clock", std::vector<double>{c.time_s, static_cast<double>(c.step),
                                     static_cast<double>(c.exchanges),
                                     static_cast<double>(c.bytes_exchanged),
                                     static_cast<double>(c.bytes_in_shared_memory), next_time_s_});
  a.put("plan", std::vector<double>{run_.plan.dt_s, static_cast<double>(run_.plan.coupling_interval)});
  a.put_scalar("wall_time_s", c.wall_before_s + wall_s);
  save_named_values(a, "scalars", c.scalars);
  run_.recorder.save_state(a);
  run_.observers.each([&](const RunObserver& o) { o.save_state(a); });
}

void RunCheckpoints::load(const state::StateArchive& a) {
  RunClock& c = run_.clock;
  const auto values = a.values("clock", 6);
  c.time_s = values[0];
  c.step = static_cast<std::uint64_t>(values[1]);
  c.exchanges = static_cast<std::uint64_t>(values[2]);
  c.bytes_exchanged = static_cast<std::uint64_t>(values[3]);
  c.bytes_in_shared_memory = static_cast<std::uint64_t>(values[4]);
  next_time_s_ = values[5];
  c.wall_before_s = a.scalar("wall_time_s");
  c.scalars = load_named_values(a, "scalars");
  run_.recorder.load_state(a);
  run_.observers.each([&](RunObserver& o) { o.load_state(a); });
}

void RunCheckpoints::restore(const Checkpoint& c) {
  const auto start = clock_type::now();
  const auto plan = c.parts.at("coupler").values("plan", 2);
  if (plan[0] != run_.plan.dt_s || plan[1] != static_cast<double>(run_.plan.coupling_interval)) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "the checkpoint's run stepped dt = %.17g s with N = %.0f, this one would step "
                  "dt = %.17g s with N = %u",
                  plan[0], plan[1], run_.plan.dt_s, run_.plan.coupling_interval);
    throw PlanError(line);
  }
  if (!c.parts.count("dem") || (run_.modules.fluid() && !c.parts.count("fluid"))) {
    throw PlanError("the checkpoint holds no state for a module of this scene");
  }
  run_.modules.load_states(c);
  load(c.parts.at("coupler"));
  std::size_t bytes = 0;
  for (const auto& [name, part] : c.parts) bytes += part.payload_bytes();
  std::fprintf(stderr, "resume     %.3g MB of state handed back to the modules in %.3g s\n",
               bytes / 1e6, seconds_since(start));
}

void RunCheckpoints::write_now(const char* why, double wall_s) {
  const auto start = clock_type::now();
  const RunClock& clock = run_.clock;
  Checkpoint c;
  c.rockcut_version = ROCKCUT_VERSION;
  c.protocol_version = wire::kProtocolVersion;
  c.scene_text = run_.loaded.effective_text();
  c.scene_path = run_.loaded.path.string();
  c.overrides = run_.loaded.overrides;
  c.step = clock.step;
  c.time_s = clock.time_s;
  try {
    run_.modules.save_states(c);
  } catch (const wire::ModuleFailure& e) {
    if (!e.refused()) throw;
    // A module that cannot save its state (a third party's, say): the run goes on without.
    std::fprintf(stderr, "\ncheckpoint  none written: %s; checkpoints are off for this run\n",
                 e.what());
    enabled_ = false;
    set_graceful_stop(false);
    return;
  }
  save(c.parts["coupler"], wall_s);
  std::size_t bytes = 0;
  for (const auto& [name, part] : c.parts) bytes += part.payload_bytes();
  const fs::path dir = run_.options.out_dir / "checkpoints";
  try {
    run_.recorder.file().flush();  // run.h5 on disk holds at least what the checkpoint says
    const fs::path file = write_checkpoint(dir, c);
    prune_checkpoints(dir, run_.loaded.scene.output().checkpoints_kept());
    std::fprintf(stderr, "\ncheckpoint  %s at t = %.6g s (step %llu): %s, %.3g MB in %.3g s\n", why,
                 clock.time_s, static_cast<unsigned long long>(clock.step), file.c_str(),
                 bytes / 1e6, seconds_since(start));
  } catch (const std::exception& e) {
    // The run itself is fine: say so and go on (the previous checkpoint stays).
    std::fprintf(stderr, "\ncheckpoint  not written (%s): %s\n", why, e.what());
  }
}

void RunCheckpoints::after_exchange(double wall_s) {
  if (!enabled_) return;
  if (take_checkpoint_request()) requested_ = true;
  const RunClock& clock = run_.clock;
  const bool last = run_.scheme.done(clock) || run_.observers.ends_run();
  const bool stopping = stop_signal() != 0 && !last;
  const double interval = run_.loaded.scene.output().checkpoint_interval_s();
  const bool sim_due = interval > 0 && clock.time_s >= next_time_s_ - 0.5 * run_.plan.dt_s;
  const bool wall_due = run_.options.checkpoint_every_s > 0 &&
                        wall_s - wall_at_last_s_ >= run_.options.checkpoint_every_s;
  if (!(due_ || requested_ || stopping || sim_due || wall_due)) return;
  if (last && !stopping) return;  // the end of the run writes one anyway
  if (!run_.scheme.between_steps()) {
    due_ = true;  // the next exchange completes its step (DESIGN section 3)
    return;
  }
  const char* why = stopping ? "stop" : requested_ ? "SIGUSR1" : sim_due ? "interval" : "wall time";
  due_ = false;
  requested_ = false;
  if (sim_due) next_time_s_ = (std::floor(clock.time_s / interval + 0.5) + 1.0) * interval;
  wall_at_last_s_ = wall_s;
  write_now(why, wall_s);
  if (stopping) throw wire::Interrupted();
}

}  // namespace rockcut::coupler
