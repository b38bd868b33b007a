// What a run does to its output directory: one run at a time (a lock naming the other's pid), a
// fresh run drops what an earlier one left (summary.json, checkpoints) so that nothing there passes
// for its own, a link planted where run.h5 goes is not followed, and a long TMPDIR does not break
// the module sockets.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <fstream>
#include <thread>

#include "integration/h5_read.hpp"
#include "integration/process_helpers.hpp"
#include "integration/small_cuts.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::vector<std::string> kShort = {"--set", "time.end_time_s=0.002"};

TEST(OutDir, ASecondRunIntoTheSameDirectoryIsRefusedNamingTheFirst) {
  const fs::path dir = fresh_dir("out_dir_lock");
  const fs::path out = dir / "out";
  std::vector<std::string> first = {bin("coupler"), "run",   kDryReducedScene,      "--out",
                                    out.string(),   "--set", "time.end_time_s=0.01"};
  const Spawned a = spawn(first, dir, "first");
  KillOnExit guard{a.pid};
  while (!fs::exists(out / "run.h5")) ASSERT_FALSE(wait_exit(a.pid, 5ms).has_value());
  std::string err;
  std::vector<std::string> second = {bin("coupler"), "run", kDryReducedScene, "--out",
                                     out.string()};
  second.insert(second.end(), kShort.begin(), kShort.end());
  EXPECT_EQ(run(second, dir, "second", nullptr, &err), 2);
  EXPECT_NE(err.find("is in use by another run (coupler pid " + std::to_string(a.pid) + ")"),
            std::string::npos)
      << err;
  ASSERT_EQ(wait_exit(a.pid, 120s).value_or(-1), 0);
  const H5Reader h5(out / "run.h5");  // the first run's output is whole
  EXPECT_FALSE(h5.doubles("/timeseries/time_s").empty());
  // Once it has ended, the directory is free again, and its run is replaced only when asked.
  EXPECT_EQ(run(second, dir, "third", nullptr, &err), 2);
  EXPECT_NE(err.find("holds the output of an earlier run (run.h5): give --overwrite"),
            std::string::npos)
      << err;
  second.push_back("--overwrite");
  EXPECT_EQ(run(second, dir, "fourth", nullptr, &err), 0) << err;
}

TEST(OutDir, AFreshRunDropsTheSummaryAndCheckpointsOfAnEarlierOne) {
  const fs::path dir = fresh_dir("out_dir_fresh");
  const CouplerRun earlier = run_coupler(kDryReducedScene, kShort, dir, 120000ms);
  ASSERT_EQ(earlier.code, 0) << earlier.err;
  ASSERT_TRUE(fs::exists(earlier.out / "summary.json"));
  ASSERT_TRUE(fs::exists(earlier.out / "checkpoints"));
  std::vector<std::string> argv = {
      bin("coupler"),       "run",         kDryReducedScene, "--out",
      earlier.out.string(), "--overwrite", "--set",          "time.end_time_s=0.05"};
  const Spawned s = spawn(argv, dir, "fresh");
  KillOnExit guard{s.pid};
  // Killed early: what is left must not pair the earlier summary with the new run.h5.
  while (fs::exists(earlier.out / "summary.json")) {
    ASSERT_FALSE(wait_exit(s.pid, 5ms).has_value()) << "ended before it had started its output";
  }
  kill(s.pid, SIGKILL);
  wait_exit(s.pid, 30s);
  EXPECT_FALSE(fs::exists(earlier.out / "summary.json"));
  EXPECT_FALSE(fs::exists(earlier.out / "checkpoints" / "checkpoint_000000011381.h5"));
}

TEST(OutDir, ALinkWhereRunH5GoesIsNotFollowed) {
  const fs::path dir = fresh_dir("out_dir_link");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  const fs::path victim = dir / "precious.txt";
  std::ofstream(victim) << "keep me\n";
  fs::create_symlink(victim, out / "run.h5");
  std::vector<std::string> args = kShort;
  args.push_back("--overwrite");  // something is where run.h5 goes
  const CouplerRun r = run_coupler(kDryReducedScene, args, dir, 120000ms);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(victim), "keep me\n");
  EXPECT_FALSE(fs::is_symlink(out / "run.h5"));
}

TEST(OutDir, ALongTmpdirStillRunsAndLeavesNothingBehind) {
  const fs::path dir = fresh_dir("out_dir_tmpdir");
  fs::path tmp = dir / std::string(90, 't');
  fs::create_directories(tmp);
  ASSERT_EQ(setenv("TMPDIR", tmp.c_str(), 1), 0);
  const CouplerRun r = run_coupler(source("cases/cutting/saturated_reduced.pbtxt"), kShort, dir,
                                   120000ms);
  unsetenv("TMPDIR");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::is_empty(tmp));
}

TEST(OutDir, ATmpdirThatIsNoDirectoryIsBadSettingsNamedOnOneLine) {
  // Missing, or a regular file: exit 2 naming TMPDIR and what to do, no module started, not a
  // module failure (exit 3) with a raw "filesystem error: temp_directory_path".
  const fs::path dir = fresh_dir("out_dir_bad_tmpdir");
  const fs::path file = dir / "a_file";
  std::ofstream(file) << "x";
  for (const fs::path& tmp : {dir / "missing", file}) {
    ASSERT_EQ(setenv("TMPDIR", tmp.c_str(), 1), 0);
    const CouplerRun r = run_coupler(source("cases/cutting/saturated_reduced.pbtxt"), kShort, dir,
                                     120000ms);
    unsetenv("TMPDIR");
    EXPECT_EQ(r.code, 2) << tmp << "\n" << r.err;
    EXPECT_NE(r.err.find("TMPDIR=" + tmp.string() + " is not a directory"), std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("filesystem error"), std::string::npos) << r.err;
  }
}

// At a file-size limit (as on a full disk) the run stops before run.h5 would pass it, with one
// line naming the file and the cause, exit code 5 and a summary.json that says failed; never a
// signal. (tests/python/full_disk_test.py checks that run.h5 then reads whole, at ten moments.)
TEST(OutDir, AFileSizeLimitStopsTheRunWithExitCode5AndASummary) {
#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
  // clang 14's TSan runtime takes SIGBUS in libomp's start-up under any `ulimit -f` (a 7-line
  // OpenMP program does too; without TSan, or without OpenMP, it runs), so the DEM module cannot
  // start here: the limit is tested by the regular build (docs/sanitizers.md).
  GTEST_SKIP() << "TSan with libomp cannot run under a file-size limit";
#endif
#endif
  const fs::path dir = fresh_dir("out_dir_full");
  const fs::path out = dir / "out";
  std::string err;
  const int code = run({"/bin/sh", "-c",
                        "ulimit -f 300; exec " + bin("coupler") + " run " + kDryReducedScene +
                            " --out " + out.string() + " --set time.end_time_s=0.01"},
                       dir, "full", nullptr, &err);
  EXPECT_EQ(code, 5) << err;
  // dash's `ulimit -f` counts 512-byte blocks: 300 of them.
  EXPECT_NE(err.find("run.h5: the file-size limit (ulimit -f) of 153600 bytes"), std::string::npos)
      << err;
  const std::string summary = read_file(out / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"failed\""), std::string::npos) << summary;
}

// A scene named by a bare file name in the working directory, with a title that is not UTF-8:
// it runs, and summary.json stays JSON (the bad byte becomes U+FFFD).
TEST(OutDir, ABareSceneNameAndALatin1TitleRun) {
  const fs::path dir = fresh_dir("out_dir_bare");
  std::ofstream(dir / "s.pbtxt") << "base: \"" << kDryReducedScene << "\"\ntitle: \"caf\xe9\"\n";
  std::string err;
  const int code = run({"/bin/sh", "-c",
                        "cd " + dir.string() + " && exec " + bin("coupler") +
                            " run s.pbtxt --out out --set time.end_time_s=0.0005"},
                       dir, "bare", nullptr, &err);
  ASSERT_EQ(code, 0) << err;
  const std::string summary = read_file(dir / "out" / "summary.json");
  EXPECT_NE(summary.find("\"title\": \"caf\\ufffd\""), std::string::npos) << summary;
}

// A coupler stopped (Ctrl-Z, a laptop asleep) for longer than coupling.timeout_s does not blame
// its modules for the time it was not running.
TEST(Suspend, ACouplerStoppedLongerThanTheTimeoutCarriesOn) {
  const fs::path dir = fresh_dir("suspend");
  std::vector<std::string> argv = {bin("coupler"), "run", source("cases/cutting/saturated_reduced.pbtxt"),
                                   "--out", (dir / "out").string(), "--set", "coupling.timeout_s=1",
                                   "--set", "time.end_time_s=0.004"};
  const Spawned s = spawn(argv, dir, "suspended");
  KillOnExit guard{s.pid};
  while (!fs::exists(dir / "out" / "run.h5")) ASSERT_FALSE(wait_exit(s.pid, 5ms).has_value());
  kill(s.pid, SIGSTOP);
  std::this_thread::sleep_for(3s);
  kill(s.pid, SIGCONT);
  EXPECT_EQ(wait_exit(s.pid, 120s).value_or(-1), 0) << read_file(s.err_file);
}

// A coupler killed by SIGKILL cannot remove its private socket directory: the next run does.
TEST(OutDir, TheSocketDirectoryOfAKilledCouplerIsRemovedByTheNextRun) {
  const fs::path dir = fresh_dir("out_dir_orphan");
  // A short TMPDIR of its own (a long one gives way to /tmp, where other runs are).
  std::string templ = "/tmp/rcXXXXXX";
  ASSERT_NE(mkdtemp(templ.data()), nullptr);
  const fs::path tmp = templ;
  ASSERT_EQ(setenv("TMPDIR", tmp.c_str(), 1), 0);
  std::vector<std::string> argv = {
      bin("coupler"),        "run", kDryReducedScene, "--out", (dir / "killed").string(), "--set",
      "time.end_time_s=0.05"};
  const Spawned s = spawn(argv, dir, "killed");
  {
    KillOnExit guard{s.pid};
    while (!fs::exists(dir / "killed" / "run.h5")) ASSERT_FALSE(wait_exit(s.pid, 5ms).has_value());
    kill(s.pid, SIGKILL);
    wait_exit(s.pid, 30s);
  }
  EXPECT_FALSE(fs::is_empty(tmp)) << "the killed coupler's directory";
  const CouplerRun next = run_coupler(kDryReducedScene, kShort, dir, 120000ms);
  unsetenv("TMPDIR");
  EXPECT_EQ(next.code, 0) << next.err;
  EXPECT_TRUE(fs::is_empty(tmp));
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace rockcut::test
