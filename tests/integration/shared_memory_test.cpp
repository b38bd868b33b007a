// The paper-scale cut's arrays over ipc:// go through shared memory (wire/shared_payload.hpp):
// the same bits as through frames and inproc, and no segment outlives the run, even when a module
// is killed.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <thread>

#include "integration/h5_read.hpp"
#include "integration/process_helpers.hpp"
#include "integration/summary_values.hpp"
#include "output/summary_json.hpp"
#include "support/summary_parser.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;
using coupler::Summary;
using namespace std::chrono_literals;

const std::string kPaperScene = source("cases/cutting/saturated.pbtxt");

// The segments of process `pid` that exist now.
std::vector<std::string> segments_of(pid_t pid) {
  const std::string prefix = "rockcut." + std::to_string(pid) + ".";
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator("/dev/shm", ec)) {
    const std::string f = e.path().filename().string();
    if (f.starts_with(prefix)) names.push_back(f);
  }
  return names;
}

// 55,177 discs: positions and forces are 883 kB per exchange each, far above the 64 KiB at which
// arrays move to shared memory. About 23 exchanges (dt 4.4e-8 s, N = 3), a time-series row every
// 12 steps (the ApplyForces round trip) and frames at 0, 1, 2, 3 us (the FrameRequest replies).
fs::path run_paper_stretch(const std::string& name, const std::string& transport) {
  const fs::path dir = fresh_dir("shared_memory_" + name);
  std::string out, err;
  const int code = run({bin("coupler"), "run", kPaperScene, "--out", (dir / "out").string(),
                        "--transport", transport, "--set", "time.end_time_s=3e-6", "--set",
                        "output.frame_interval_s=1e-6", "--set", "output.timeseries_every_steps=12",
                        "--set", "dem.tool.start_gap_m=0"},
                       dir, "coupler", &out, &err);
  EXPECT_EQ(code, 0) << err;
  return dir / "out";
}

TEST(SharedMemory, PaperScaleCutHasTheSameBitsThroughSharedMemoryFramesAndInproc) {
  const fs::path shm = run_paper_stretch("ipc", "ipc");
  setenv("ROCKCUT_WIRE_SHARED_MEMORY", "0", 1);  // inherited by the modules the coupler starts
  const fs::path frames = run_paper_stretch("ipc_frames", "ipc");
  unsetenv("ROCKCUT_WIRE_SHARED_MEMORY");
  const fs::path inproc = run_paper_stretch("inproc", "inproc");

  const Summary a = coupler::read_summary(shm / "summary.json"), b = coupler::read_summary(frames / "summary.json"),
                c = coupler::read_summary(inproc / "summary.json");
  // Every per-particle array of the exchanges (positions and forces) went through shared memory;
  // only the wall segments (a few hundred bytes) stayed in frames.
  const double per_exchange = number(a, "bytes_exchanged") / number(a, "exchanges");
  EXPECT_GT(number(a, "bytes_in_shared_memory"), 0.99 * number(a, "bytes_exchanged"));
  EXPECT_GT(per_exchange, 2 * 55177 * 2 * sizeof(double) - 1.0);
  EXPECT_EQ(number(b, "bytes_in_shared_memory"), 0.0);
  EXPECT_EQ(number(c, "bytes_in_shared_memory"), 0.0);
  EXPECT_EQ(number(a, "bytes_exchanged"), number(b, "bytes_exchanged"));
  EXPECT_EQ(number(a, "bytes_exchanged"), number(c, "bytes_exchanged"));

  H5Reader ha(shm / "run.h5"), hb(frames / "run.h5"), hc(inproc / "run.h5");
  const auto series = ha.members("/timeseries");
  ASSERT_GE(series.size(), 10u);
  for (const std::string& name : series) {
    if (name == "step") continue;  // uint64, compared through time_s
    const auto va = ha.doubles("/timeseries/" + name);
    EXPECT_TRUE(bit_identical(va, hb.doubles("/timeseries/" + name))) << name << " shm vs frames";
    EXPECT_TRUE(bit_identical(va, hc.doubles("/timeseries/" + name))) << name << " shm vs inproc";
  }
  const auto frame_names = ha.members("/frames");
  ASSERT_EQ(frame_names.size(), 4u);
  for (const std::string& f : frame_names) {
    for (const std::string field : {"position", "pressure"}) {
      const std::string p = "/frames/" + f + "/" + field;
      EXPECT_TRUE(bit_identical(ha.doubles(p), hb.doubles(p))) << p << " shm vs frames";
      EXPECT_TRUE(bit_identical(ha.doubles(p), hc.doubles(p))) << p << " shm vs inproc";
    }
  }
}

TEST(SharedMemory, NoSegmentOutlivesTheRunWhenAModuleIsKilled) {
  const fs::path dir = fresh_dir("shared_memory_kill");
  const Spawned coupler = spawn({bin("coupler"), "run", kPaperScene, "--out", (dir / "out").string(),
                                 "--set", "time.end_time_s=0.01", "--set", "output.frame_interval_s=0",
                                 "--set", "dem.tool.start_gap_m=0"},
                                dir, "coupler");
  const KillOnExit guard{coupler.pid};
  const pid_t dem = wait_for_child_named(coupler.pid, "dem_module", 20000ms);
  const pid_t fluid = wait_for_child_named(coupler.pid, "fluid_module", 20000ms);
  ASSERT_GT(dem, 0);
  ASSERT_GT(fluid, 0);
  // Exchanging: both modules have written their arrays into their segments.
  for (int i = 0; i < 1000 && (segments_of(dem).empty() || segments_of(fluid).empty()); ++i) {
    std::this_thread::sleep_for(20ms);
  }
  ASSERT_FALSE(segments_of(fluid).empty()) << "the fluid never wrote to shared memory";
  ASSERT_FALSE(segments_of(dem).empty()) << "the DEM never wrote to shared memory";
  kill(fluid, SIGKILL);
  const auto code = wait_exit(coupler.pid, 20000ms);
  ASSERT_TRUE(code.has_value()) << "the coupler did not stop after its fluid died";
  EXPECT_EQ(*code, 3);
  EXPECT_TRUE(segments_of(fluid).empty()) << "the killed fluid's segments were left behind";
  EXPECT_TRUE(segments_of(dem).empty()) << "the DEM's segments were left behind";
}

TEST(SharedMemory, AnIpcRunRemovesWhatDeadProcessesLeftBehind) {
  // A module killed together with its coupler (SIGKILL: nobody unlinks) leaves segments named by
  // its pid. Make such a pid: a child that has exited and been reaped.
  const pid_t dead = fork();
  if (dead == 0) _exit(0);
  ASSERT_GT(dead, 0);
  waitpid(dead, nullptr, 0);
  const std::string orphan = "/rockcut." + std::to_string(dead) + ".0-1.force.0.v1";
  const std::string mine = "/rockcut." + std::to_string(getpid()) + ".99-1.force.0.v1";
  for (const std::string& name : {orphan, mine}) {
    const int fd = shm_open(name.c_str(), O_RDWR | O_CREAT, 0600);
    ASSERT_GE(fd, 0) << name;
    close(fd);
  }
  const fs::path dir = fresh_dir("shared_memory_orphans");
  std::string out, err;
  EXPECT_EQ(run({bin("coupler"), "run", source("cases/verification/pressure_gradient.pbtxt"),
                 "--out", (dir / "out").string()},
                dir, "coupler", &out, &err),
            0)
      << err;
  EXPECT_TRUE(segments_of(dead).empty()) << "the dead process's segment is still there";
  EXPECT_EQ(segments_of(getpid()).size(), 1u) << "a live process's segment was removed";
  shm_unlink(mine.c_str());
}

}  // namespace
}  // namespace rockcut::test
