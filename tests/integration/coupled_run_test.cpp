// End-to-end runs of the real executables: the analytical scenes over every transport.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <cmath>
#include <cstring>

#include "integration/h5_read.hpp"
#include "integration/process_helpers.hpp"
#include "integration/summary_values.hpp"
#include "output/summary_json.hpp"
#include "support/summary_parser.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;
using coupler::Summary;

const std::string kPressureGradient = source("cases/verification/pressure_gradient.pbtxt");

// Runs the pressure-gradient scene over `transport` and returns the output directory.
fs::path run_pressure_gradient(const std::string& transport, std::string* err = nullptr) {
  const fs::path dir = fresh_dir("pressure_gradient_" + transport);
  std::vector<std::string> argv = {bin("coupler"), "run", kPressureGradient, "--out",
                                   (dir / "out").string(), "--transport", transport};
  std::vector<Spawned> modules;
  if (transport == "tcp") {
    // Modules started by hand, as a user on another host would.
    const std::string dem = "tcp://127.0.0.1:" + std::to_string(free_tcp_port());
    const std::string fluid = "tcp://127.0.0.1:" + std::to_string(free_tcp_port());
    modules.push_back(spawn({bin("dem_module"), "--bind", dem}, dir, "dem"));
    modules.push_back(spawn({bin("fluid_module"), "--bind", fluid}, dir, "fluid"));
    argv.insert(argv.end(), {"--dem-endpoint", dem, "--fluid-endpoint", fluid});
  }
  std::string out, e;
  const int code = run(argv, dir, "coupler", &out, &e);
  EXPECT_EQ(code, 0) << e;
  for (const Spawned& m : modules) {
    // A hand-started module serves one session and exits after Shutdown.
    EXPECT_EQ(wait_exit(m.pid, std::chrono::milliseconds(5000)), 0);
  }
  if (err) *err = e;
  return dir / "out";
}

TEST(CoupledRun, PressureGradientFollowsTheAnalyticalSolutionToRoundOff) {
  const fs::path out = run_pressure_gradient("ipc");
  const Summary s = coupler::read_summary(out / "summary.json");
  EXPECT_EQ(text(s, "status"), "completed");
  // Tolerance 1e-11: velocity Verlet is exact for constant acceleration; round-off grows like
  // steps * eps * |x| / |displacement| ~ 1e-12 (see the scene file).
  EXPECT_LT(number(s, "error_max_rel"), 1e-11);
  EXPECT_EQ(number(s, "steps"), 1000);
  EXPECT_EQ(number(s, "particles"), 200);
  EXPECT_GT(number(s, "wall_time_s"), 0.0);
  EXPECT_GT(number(s, "particle_steps_per_s"), 0.0);

  // Check the stored frames independently of the coupler's own verification: the last frame
  // against x0 + v0 t + a t^2/2 with a = g - grad p / rho.
  H5Reader h5(out / "run.h5");
  const auto frames = h5.members("/frames");
  ASSERT_EQ(frames.size(), 6u);  // t = 0, 0.002, ..., 0.01
  const auto x0 = h5.doubles("/frames/000000/position");
  const auto x = h5.doubles("/frames/" + frames.back() + "/position");
  const double t = h5.doubles("/timeseries/time_s").back();
  const double ax = 2.8e5 / 2800, ay = -9.81 - 5.6e4 / 2800, vx = 0.1, vy = 0.0;
  ASSERT_EQ(x.size(), 400u);
  for (std::size_t k = 0; k < x.size(); k += 2) {
    EXPECT_NEAR(x[k], x0[k] + vx * t + 0.5 * ax * t * t, 1e-13);
    EXPECT_NEAR(x[k + 1], x0[k + 1] + vy * t + 0.5 * ay * t * t, 1e-13);
  }
}

TEST(CoupledRun, TransportsGiveBitIdenticalResults) {
  const fs::path ipc = run_pressure_gradient("ipc");
  const fs::path inproc = run_pressure_gradient("inproc");
  const fs::path tcp = run_pressure_gradient("tcp");
  H5Reader a(ipc / "run.h5"), b(inproc / "run.h5"), c(tcp / "run.h5");
  const auto series = a.members("/timeseries");
  ASSERT_GE(series.size(), 3u);
  for (const std::string& name : series) {
    const auto va = a.doubles("/timeseries/" + name);
    if (name == "step") continue;  // uint64, compared through time_s
    EXPECT_TRUE(bit_identical(va, b.doubles("/timeseries/" + name))) << name << " ipc vs inproc";
    EXPECT_TRUE(bit_identical(va, c.doubles("/timeseries/" + name))) << name << " ipc vs tcp";
  }
  for (const std::string& frame : a.members("/frames")) {
    const std::string p = "/frames/" + frame + "/position";
    EXPECT_TRUE(bit_identical(a.doubles(p), b.doubles(p))) << p;
    EXPECT_TRUE(bit_identical(a.doubles(p), c.doubles(p))) << p;
  }
  EXPECT_EQ(a.root_attribute("transport"), "ipc");
  EXPECT_EQ(b.root_attribute("transport"), "inproc");
  EXPECT_EQ(c.root_attribute("transport"), "tcp");
}

TEST(CoupledRun, DrySceneStartsNoFluidProcessAndIsExact) {
  const fs::path dir = fresh_dir("free_fall");
  const Spawned s = spawn({bin("coupler"), "run", source("cases/verification/free_fall.pbtxt"),
                           "--out", (dir / "out").string()},
                          dir, "coupler");
  // Watch the coupler's children while it runs: only a dem_module may appear.
  std::vector<std::string> seen;
  std::optional<int> code;
  while (!(code = wait_exit(s.pid, std::chrono::milliseconds(2)))) {
    for (pid_t kid : children_of(s.pid)) {
      // A child between fork and exec still carries the coupler's name.
      const std::string name = command_name(kid);
      if (name != "coupler") seen.push_back(name);
    }
  }
  EXPECT_EQ(*code, 0) << read_file(s.err_file);
  for (const std::string& name : seen) EXPECT_EQ(name, "dem_module");
  EXPECT_NE(read_file(s.err_file).find("no fluid process"), std::string::npos);
  const Summary summary = coupler::read_summary(dir / "out" / "summary.json");
  EXPECT_LT(number(summary, "error_max_rel"), 1e-11);
  EXPECT_EQ(text(summary, "fluid_model"), "none");
  EXPECT_EQ(text(summary, "coupling_scheme"), "dry");  // coupler/schemes/dry_scheme.hpp
  // Dry: one message per output event, not per step.
  EXPECT_LT(number(summary, "exchanges"), number(summary, "steps") / 10);
}

TEST(CoupledRun, OnlyTheFieldsTheFluidNeedsCrossTheWire) {
  // prescribed_gradient needs no kinematics: per exchange only the force array travels back.
  const fs::path out = run_pressure_gradient("inproc");
  const Summary s = coupler::read_summary(out / "summary.json");
  const double per_exchange = number(s, "bytes_exchanged") / number(s, "exchanges");
  EXPECT_EQ(per_exchange, 200 * 2 * sizeof(double));
}

}  // namespace
}  // namespace rockcut::test
