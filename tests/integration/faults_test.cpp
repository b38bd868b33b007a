// Faults: a module killed, a module that stops answering, a version mismatch, a signal to the
// coupler. Each must give a one-line error naming the module, a readable partial run.h5, a non-zero
// exit and no orphan process.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <thread>

#include "integration/h5_read.hpp"
#include "integration/process_helpers.hpp"
#include "output/summary_json.hpp"
#include "support/summary_parser.hpp"
#include "wire/protocol.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string kPressureGradientScene = source("cases/verification/pressure_gradient.pbtxt");

// A long run (1e7 steps) that writes a frame every 1000 steps, so frames exist when we strike.
Spawned start_long_run(const fs::path& dir, std::vector<std::string> extra = {}) {
  std::vector<std::string> argv = {bin("coupler"),
                                   "run",
                                   kPressureGradientScene,
                                   "--out",
                                   (dir / "out").string(),
                                   "--set",
                                   "time.end_time_s=100",
                                   "--set",
                                   "output.frame_interval_s=0.01",
                                   "--set",
                                   "verification.tolerance_rel=1"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return spawn(argv, dir, "coupler");
}

// Waits until run.h5 holds at least two frames (the run is well under way).
void wait_for_frames(const fs::path& out) {
  for (int i = 0; i < 500; ++i) {
    std::this_thread::sleep_for(20ms);
    try {
      H5Reader h5(out / "run.h5");
      if (h5.members("/frames").size() >= 2) return;
    } catch (const std::exception&) {
    }
  }
  FAIL() << "no frames appeared in " << out;
}

pid_t child_named(pid_t parent, const std::string& name) {
  return wait_for_child_named(parent, name, 5000ms);
}

void expect_readable_partial_output(const fs::path& out, const std::string& status) {
  H5Reader h5(out / "run.h5");
  EXPECT_GE(h5.members("/frames").size(), 2u);
  EXPECT_FALSE(h5.doubles("/timeseries/time_s").empty());
  EXPECT_EQ(h5.root_attribute("status").rfind(status, 0), 0u) << h5.root_attribute("status");
  const auto summary = coupler::read_summary(out / "summary.json");
  EXPECT_EQ(std::get<std::string>(*summary.get("status")), status);
}

TEST(Faults, KilledModuleIsNamedOutputStaysReadableNoOrphans) {
  const fs::path dir = fresh_dir("sigkill");
  const Spawned coupler = start_long_run(dir);
  const KillOnExit guard{coupler.pid};
  const pid_t dem = child_named(coupler.pid, "dem_module");
  const pid_t fluid = child_named(coupler.pid, "fluid_module");
  ASSERT_GT(dem, 0);
  ASSERT_GT(fluid, 0);
  wait_for_frames(dir / "out");
  kill(dem, SIGKILL);
  const auto code = wait_exit(coupler.pid, 10000ms);
  ASSERT_TRUE(code.has_value()) << "the coupler did not stop after its DEM died";
  EXPECT_EQ(*code, 3);
  const std::string err = read_file(coupler.err_file);
  EXPECT_NE(err.find("error: dem_module (pid " + std::to_string(dem) +
                     ")"), std::string::npos) << err;
  EXPECT_NE(err.find("killed by signal 9 (SIGKILL)"), std::string::npos) << err;
  expect_readable_partial_output(dir / "out", "failed");
  EXPECT_TRUE(is_gone(dem));
  EXPECT_TRUE(is_gone(fluid)) << "fluid_module outlived the run";
}

TEST(Faults, StalledModuleIsDetectedWithinTheTimeout) {
  const fs::path dir = fresh_dir("stall");
  const Spawned coupler = start_long_run(dir, {"--set", "coupling.timeout_s=1"});
  const KillOnExit guard{coupler.pid};
  const pid_t dem = child_named(coupler.pid, "dem_module");
  const pid_t fluid = child_named(coupler.pid, "fluid_module");
  ASSERT_GT(fluid, 0);
  wait_for_frames(dir / "out");
  kill(fluid, SIGSTOP);  // alive but silent
  const auto start = std::chrono::steady_clock::now();
  const auto code = wait_exit(coupler.pid, 15000ms);
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(code.has_value()) << "the coupler did not notice the stalled fluid module";
  EXPECT_EQ(*code, 3);
  // Detected after the 1 s timeout, plus at most the clean shutdown of the other module (2 s grace
  // for the stalled one, 0.5 s after SIGTERM) and scheduling slack.
  EXPECT_LT(waited, 6.0);
  const std::string err = read_file(coupler.err_file);
  EXPECT_NE(err.find("fluid_module (pid " + std::to_string(fluid) + "): stopped answering"),
            std::string::npos) << err;
  expect_readable_partial_output(dir / "out", "failed");
  EXPECT_TRUE(is_gone(fluid));
  EXPECT_TRUE(is_gone(dem));
}

TEST(Faults, VersionMismatchedModuleIsRefusedNamingBothSides) {
  const fs::path dir = fresh_dir("version");
  std::string out, err;
  const int code =
      run({bin("coupler"), "run", kPressureGradientScene, "--out", (dir / "out").string(), "--set",
           "dem.executable=" + std::string(ROCKCUT_BIN_DIR) + "/../tests/fake_module"},
          dir, "coupler", &out, &err);
  EXPECT_EQ(code, 3);
  EXPECT_NE(err.find("protocol version mismatch"), std::string::npos) << err;
  EXPECT_NE(err.find("speaks protocol " + std::to_string(rockcut::wire::kProtocolVersion)), std::string::npos) << err;
  EXPECT_NE(err.find("fake_module 9.9.9 speaks protocol 999"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "out" / "run.h5")) << "nothing may be written for a refused run";
}

TEST(Faults, UnknownFluidModelIsRefusedListingTheOffer) {
  const fs::path dir = fresh_dir("model");
  std::string out, err;
  const int code = run({bin("coupler"), "run", kPressureGradientScene, "--out",
                        (dir / "out").string(), "--set", "fluid.model=lattice_boltzmann"},
                       dir, "coupler", &out, &err);
  EXPECT_EQ(code, 2);  // the scene names a model the module does not offer: bad input
  EXPECT_NE(err.find("lattice_boltzmann"), std::string::npos) << err;
  EXPECT_NE(err.find("offers: explicit, implicit, prescribed_gradient"), std::string::npos) << err;
}

class StopSignal : public ::testing::TestWithParam<int> {};

TEST_P(StopSignal, ShutsEverythingDownWithOutputClosed) {
  const int sig = GetParam();
  const fs::path dir = fresh_dir("signal_" + std::to_string(sig));
  const Spawned coupler = start_long_run(dir);
  const KillOnExit guard{coupler.pid};
  const pid_t dem = child_named(coupler.pid, "dem_module");
  const pid_t fluid = child_named(coupler.pid, "fluid_module");
  wait_for_frames(dir / "out");
  kill(coupler.pid, sig);
  const auto code = wait_exit(coupler.pid, 10000ms);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 128 + sig);
  expect_readable_partial_output(dir / "out", "interrupted");
  EXPECT_TRUE(is_gone(dem));
  EXPECT_TRUE(is_gone(fluid));
}

// SIGHUP: the terminal the run was started from closed (a lost ssh session).
INSTANTIATE_TEST_SUITE_P(IntTermAndHup, StopSignal, ::testing::Values(SIGINT, SIGTERM, SIGHUP));

// `nohup coupler run ...`: started with SIGHUP ignored, the run outlives its terminal.
TEST(Faults, HangUpUnderNohupIsIgnored) {
  const fs::path dir = fresh_dir("nohup");
  const auto previous = signal(SIGHUP, SIG_IGN);  // inherited by the spawned coupler, as nohup does
  const Spawned coupler = start_long_run(dir);
  signal(SIGHUP, previous);
  const KillOnExit guard{coupler.pid};
  wait_for_frames(dir / "out");
  kill(coupler.pid, SIGHUP);
  EXPECT_FALSE(wait_exit(coupler.pid, 1000ms).has_value()) << "a hang-up under nohup stopped the run";
  kill(coupler.pid, SIGTERM);
  const auto code = wait_exit(coupler.pid, 10000ms);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 128 + SIGTERM);
  expect_readable_partial_output(dir / "out", "interrupted");
}

// `coupler run ... | head`, or a driver script killed while its run goes on: stdout's reader is
// gone before the coupler's first line. The run must finish and clean up, not die of SIGPIPE
// (exit 141) with its modules' sockets and shared memory left behind.
TEST(Faults, ClosedStdoutLetsTheRunFinish) {
  const fs::path dir = fresh_dir("closed_stdout");
  int fds[2];
  ASSERT_EQ(pipe2(fds, O_CLOEXEC), 0);
  const Spawned coupler =
      spawn({bin("coupler"), "run", kPressureGradientScene, "--out", (dir / "out").string()}, dir,
            "coupler", fds[1]);
  const KillOnExit guard{coupler.pid};
  close(fds[0]);  // no reader from here on
  close(fds[1]);
  const auto code = wait_exit(coupler.pid, 60000ms);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 0) << read_file(coupler.err_file);
  const auto summary = coupler::read_summary(dir / "out" / "summary.json");
  EXPECT_EQ(std::get<std::string>(*summary.get("status")), "completed");
}

TEST(Faults, KilledCouplerLeavesNoOrphans) {
  const fs::path dir = fresh_dir("coupler_killed");
  const Spawned coupler = start_long_run(dir);
  const KillOnExit guard{coupler.pid};
  const pid_t dem = child_named(coupler.pid, "dem_module");
  const pid_t fluid = child_named(coupler.pid, "fluid_module");
  wait_for_frames(dir / "out");
  kill(coupler.pid, SIGKILL);
  wait_exit(coupler.pid, 5000ms);
  for (int i = 0; i < 200 && !(is_gone(dem) && is_gone(fluid)); ++i) std::this_thread::sleep_for(10ms);
  EXPECT_TRUE(is_gone(dem));
  EXPECT_TRUE(is_gone(fluid));
  // Frames written before the kill are flushed and readable.
  H5Reader h5(dir / "out" / "run.h5");
  EXPECT_GE(h5.members("/frames").size(), 2u);
}

}  // namespace
}  // namespace rockcut::test
