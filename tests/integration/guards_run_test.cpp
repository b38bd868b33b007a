// Runtime guards end to end (DESIGN section 5): each guard is provoked by a scene, through the real
// coupler and dem_module. The run must stop with exit code 4, name the guard, the time, the
// particle and its position, write the state that tripped it as the last frame, and leave
// summary.json saying the run failed and why.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "integration/h5_read.hpp"
#include "integration/process_helpers.hpp"
#include "integration/summary_values.hpp"
#include "output/summary_json.hpp"
#include "support/summary_parser.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;
using coupler::Summary;

CouplerRun run_scene_text(const std::string& name, const std::string& scene_text,
                          const std::vector<std::string>& args = {}) {
  const fs::path dir = fresh_dir(name);
  const fs::path scene = dir / (name + ".pbtxt");
  std::ofstream(scene) << scene_text;
  return run_coupler(scene.string(), args, dir, std::chrono::milliseconds(60000));
}

// What every guard stop must leave behind.
void expect_stopped_by(const CouplerRun& r, const std::string& guard) {
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("(guard " + guard + ")"), std::string::npos) << r.err;
  const Summary s = coupler::read_summary(r.out / "summary.json");
  EXPECT_EQ(text(s, "status"), "failed");
  EXPECT_EQ(text(s, "failure_guard"), guard);
  EXPECT_NE(text(s, "error").find(guard + " guard"), std::string::npos);
  const double t = number(s, "failure_time_s");
  EXPECT_GT(t, 0.0);
  EXPECT_NE(r.err.find("at t = "), std::string::npos);
  // The last frame holds the state that tripped the guard: the named particle is where the
  // summary says it was.
  const H5Reader h5(r.out / "run.h5");
  EXPECT_EQ(h5.root_attribute("status").rfind("failed: " + guard, 0), 0u);
  const auto position = h5.doubles(last_frame(h5) + "/position");
  const auto i = static_cast<std::size_t>(number(s, "failure_particle"));
  ASSERT_LT(2 * i + 1, position.size());
  if (guard != "nan") {
    EXPECT_DOUBLE_EQ(position[2 * i], number(s, "failure_x_m"));
    EXPECT_DOUBLE_EQ(position[2 * i + 1], number(s, "failure_y_m"));
  }
}

// Discs on a lattice, touching, with contacts: the base of the scenes below.
std::string lattice_scene(const std::string& extra_dem, const std::string& time) {
  return "title: \"guard test\"\n"
         "time { " + time + " }\n"
         "output { timeseries_every_steps: 200 }\n"
         "dem {\n"
         "  lattice { nx: 10 ny: 10 spacing_m: 0.002 radius_m: 0.001 }\n"
         "  contact { normal_stiffness_pa: 1e10 shear_stiffness_pa: 2.5e10 friction: 0.5 }\n" +
         extra_dem + "}\n";
}

// NaN / Inf: speeds whose squares overflow (1e200 m/s) make the kinetic energy infinite at t = 0.
TEST(GuardsRun, InfiniteStateStopsTheRunAtOnce) {
  const CouplerRun r = run_scene_text(
      "guard_nan",
      lattice_scene("  initial_velocity_m_s { x: 1e200 y: 0 }\n", "end_time_s: 0.01"));
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("(guard nan)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not finite"), std::string::npos) << r.err;
  const Summary s = coupler::read_summary(r.out / "summary.json");
  EXPECT_EQ(text(s, "status"), "failed");
  EXPECT_EQ(text(s, "failure_guard"), "nan");
  EXPECT_GE(number(s, "failure_particle"), 0);
  const H5Reader h5(r.out / "run.h5");
  EXPECT_NO_THROW(last_frame(h5));
}

// Runaway kinetic energy: an undamped lattice shaken at 3.5 times the critical time step (forced
// past the refusal with time.ignore_limits) gains energy every step.
TEST(GuardsRun, RunawayKineticEnergyStopsAStepAboveTheLimit) {
  const std::string scene = lattice_scene(
      "  damping { model: \"none\" }\n  initial_velocity_m_s { x: 0.01 y: 0.02 }\n"
      "  walls { name: \"box\" closed: true vertex_m { x: -0.0011 y: -0.0011 }"
      " vertex_m { x: 0.0191 y: -0.0011 } vertex_m { x: 0.0191 y: 0.0191 }"
      " vertex_m { x: -0.0011 y: 0.0191 } }\n",
      "end_time_s: 0.01 dt_s: 1.4e-6 ignore_limits: true");
  const CouplerRun r = run_scene_text("guard_kinetic", scene);
  expect_stopped_by(r, "kinetic_energy");
  EXPECT_NE(r.err.find("WARNING time.dt_s"), std::string::npos) << r.err;
  // Stopped within one guard interval of the blow-up, long before anything overflowed.
  const Summary s = coupler::read_summary(r.out / "summary.json");
  EXPECT_LT(number(s, "failure_time_s"), 0.001);
  EXPECT_TRUE(std::isfinite(number(s, "failure_value")));
  // Without ignore_limits the same scene is refused before anything runs.
  const CouplerRun refused = run_scene_text("guard_kinetic_refused", scene,
                                            {"--set", "time.ignore_limits=false"});
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_NE(refused.err.find("exceeds the dem_module limit dem_springs"), std::string::npos);
}

// The same blow-up in a coupled run with N = 1000 DEM steps per exchange: the guard trips inside
// the DEM's split Advance, on its way through the 1000 steps (it checks every 50), and is reported
// as the guard (exit 4), not as a module that answered with too few steps (exit 3).
TEST(GuardsRun, AGuardInsideALongCoupledAdvanceIsTheGuard) {
  std::string scene = lattice_scene(
      "  damping { model: \"none\" }\n  initial_velocity_m_s { x: 0.01 y: 0.02 }\n"
      "  walls { name: \"box\" closed: true vertex_m { x: -0.0011 y: -0.0011 }"
      " vertex_m { x: 0.0191 y: -0.0011 } vertex_m { x: 0.0191 y: 0.0191 }"
      " vertex_m { x: -0.0011 y: 0.0191 } }\n",
      "end_time_s: 0.01 dt_s: 1.4e-6 ignore_limits: true");
  scene += "fluid { model: \"implicit\" smoothing_length_m: 0.005 permeability_m2: 1e-14 }\n"
           "coupling { interval: 1000 }\n";
  const CouplerRun r = run_scene_text("guard_coupled_advance", scene);
  expect_stopped_by(r, "kinetic_energy");
  const double step = number(coupler::read_summary(r.out / "summary.json"), "steps");
  EXPECT_NE(std::fmod(step, 1000.0), 0.0) << "the guard did not trip inside an Advance: " << step;
  EXPECT_EQ(r.err.find("after 1000 steps"), std::string::npos) << r.err;
}

// Excessive overlap: a platen closing at 1 cm/s on one disc resting on a floor crushes it slowly
// (no speed anywhere near the speed limit) until the overlap passes 0.25 of its radius.
TEST(GuardsRun, ExcessiveOverlapStopsAQuasiStaticCrush) {
  const std::string scene =
      "time { end_time_s: 0.05 }\n"
      "output { timeseries_every_steps: 1000 }\n"
      "dem {\n"
      "  lattice { nx: 1 ny: 1 spacing_m: 0.002 radius_m: 0.001 origin_m { x: 0 y: 0.001 } }\n"
      "  contact { normal_stiffness_pa: 1e10 shear_stiffness_pa: 2.5e10 friction: 0.5 }\n"
      "  walls { name: \"floor\" vertex_m { x: -0.01 y: 0 } vertex_m { x: 0.01 y: 0 } }\n"
      "  walls { name: \"platen\" vertex_m { x: -0.01 y: 0.002 } vertex_m { x: 0.01 y: 0.002 }"
      " velocity_m_s { x: 0 y: -0.01 } }\n"
      "}\n";
  const CouplerRun r = run_scene_text("guard_overlap", scene);
  expect_stopped_by(r, "overlap");
  const Summary s = coupler::read_summary(r.out / "summary.json");
  // Both walls' overlaps grow at half the platen speed: 0.25 mm each after 0.05 s at most. The
  // guard runs every 50 steps of 1.9e-7 s: it trips within 1e-5 s of the crossing.
  EXPECT_NEAR(number(s, "failure_time_s"), 0.05, 0.002);
  EXPECT_GT(number(s, "failure_value"), 0.25);
  EXPECT_LT(number(s, "failure_value"), 0.26);
}

// Overlaps already in the initial packing beyond the limit are refused at start-up, naming the
// field and the particle; nothing runs.
TEST(GuardsRun, InitialOverlapBeyondTheLimitIsRefused) {
  const CouplerRun r = run_scene_text(
      "guard_initial",
      "time { end_time_s: 0.001 }\n"
      "dem {\n"
      "  lattice { nx: 4 ny: 4 spacing_m: 0.0015 radius_m: 0.001 }\n"
      "  contact { normal_stiffness_pa: 1e10 shear_stiffness_pa: 2.5e10 friction: 0.5 }\n"
      "}\n");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("dem.guards.max_overlap_ratio"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("starts overlapping a neighbour or a wall by 0.5"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(r.out / "summary.json"));
}

}  // namespace
}  // namespace rockcut::test
