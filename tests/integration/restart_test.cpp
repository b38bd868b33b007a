// Checkpoint and restart, end to end through the real coupler and modules: a run stopped by
// SIGTERM after a checkpoint and resumed, and a run killed by SIGKILL (no last checkpoint) and
// resumed from the one before, write bit for bit what the uninterrupted run writes: every time
// series, every break, every frame and every summary.json value but the wall-time ones. Also a
// restart of a restart, and the refusals: a changed scene, a corrupted or truncated checkpoint
// (with the fall-back to the previous one), and nothing to resume from.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
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

constexpr int kExitBadInput = 2;

// Short cuts: 4 ms of tool travel (the first bonds break after about 3 mm), a checkpoint every
// 0.5 ms of simulated time, frames every millisecond.
std::vector<std::string> short_cut(const std::string& threads, const std::string& transport) {
  return {"--set",       "time.end_time_s=0.004", "--set", "output.checkpoint_interval_s=0.0005",
          "--set",       "output.frame_interval_s=0.001", "--set", "dem.threads=" + threads,
          "--transport", transport};
}

// Summary values that measure the machine, not the run.
const std::set<std::string> kWallFields = {"wall_time_s",  "particle_steps_per_s", "dem_busy_s",
                                           "dem_after_reply_s", "fluid_busy_s",
                                           "fluid_after_reply_s"};

// The wall-time split of summary.json (session/time_split.hpp): wall clock, not state.
bool is_time_split(const std::string& key) {
  return key == "coupler_own_s" || key.find("_phase_") != std::string::npos ||
         key.ends_with("_service_s") || key.ends_with("_request_s");
}

void expect_same_output(const fs::path& a_dir, const fs::path& b_dir, const std::string& what) {
  const H5Reader a(a_dir / "run.h5"), b(b_dir / "run.h5");
  for (const std::string group : {"/timeseries", "/breaks"}) {
    const auto names = a.members(group);
    ASSERT_FALSE(names.empty()) << what << ": " << group;
    ASSERT_EQ(names, b.members(group)) << what << ": " << group;
    for (const std::string& name : names) {
      EXPECT_TRUE(bit_identical(a.doubles(group + "/" + name), b.doubles(group + "/" + name)))
          << what << ": " << group << "/" << name;
    }
  }
  const auto frames = a.members("/frames");
  ASSERT_EQ(frames, b.members("/frames")) << what;
  for (const std::string& f : frames) {
    const std::string g = "/frames/" + f;
    const auto fields = a.members(g);
    ASSERT_EQ(fields, b.members(g)) << what << ": " << g;
    for (const std::string& field : fields) {
      EXPECT_TRUE(bit_identical(a.doubles(g + "/" + field), b.doubles(g + "/" + field)))
          << what << ": " << g << "/" << field;
    }
  }
  EXPECT_EQ(read_file(a_dir / "run.xdmf"), read_file(b_dir / "run.xdmf")) << what;
  const Summary sa = coupler::read_summary(a_dir / "summary.json");
  const Summary sb = coupler::read_summary(b_dir / "summary.json");
  ASSERT_EQ(sa.entries().size(), sb.entries().size()) << what;
  for (const auto& [key, value] : sa.entries()) {
    if (kWallFields.count(key) || is_time_split(key)) continue;
    const auto other = sb.get(key);
    ASSERT_TRUE(other.has_value()) << what << ": " << key;
    // null (NaN: a statistic the run had no sample for) on both sides is the same value.
    const double* x = std::get_if<double>(&value);
    const double* y = std::get_if<double>(&*other);
    const bool both_null = x && y && std::isnan(*x) && std::isnan(*y);
    EXPECT_TRUE(both_null || value == *other) << what << ": summary.json " << key;
  }
  EXPECT_EQ(text(sb, "status"), "completed") << what;
}

std::vector<fs::path> checkpoints(const fs::path& out) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(out / "checkpoints", ec)) {
    if (e.path().extension() == ".h5") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Starts `coupler run`, waits until `count` checkpoints have been written, sends `sig` and
// returns the exit code.
int run_until_checkpoints(const std::string& scene, const std::vector<std::string>& args,
                          const fs::path& dir, const fs::path& out, std::size_t count, int sig,
                          const std::string& tag) {
  std::vector<std::string> argv = {bin("coupler"), "run", scene, "--out", out.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  const Spawned s = spawn(argv, dir, tag);
  KillOnExit guard{s.pid};
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (checkpoints(out).size() < count && std::chrono::steady_clock::now() < deadline) {
    if (auto code = wait_exit(s.pid, 10ms)) return *code;  // ended before: the caller's check fails
  }
  kill(s.pid, sig);
  return wait_exit(s.pid, 60s).value_or(-1);
}

int resume(const fs::path& out, const std::vector<std::string>& args, const fs::path& dir,
           const std::string& tag, std::string* err = nullptr) {
  std::vector<std::string> argv = {bin("coupler"), "resume", out.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  return run(argv, dir, tag, nullptr, err, 120000ms);
}

struct Case {
  std::string scene, threads, transport;
  std::vector<std::string> sets = {};  ///< more --set options: another damping, rolling springs
  std::string tag = "";                ///< names the case when `sets` is not empty
};
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.scene << ", " << c.threads << " DEM threads, " << c.transport;
  for (const std::string& s : c.sets) *os << " " << s;
}

class Restart : public ::testing::TestWithParam<Case> {};

TEST_P(Restart, StoppedKilledAndResumedRunsMatchTheUninterruptedOneBitForBit) {
  const Case& c = GetParam();
  // A bare name is a cut; "calibration/..." another case.
  const std::string folder = c.scene.find('/') == std::string::npos ? "cutting/" : "";
  const std::string scene = source("cases/" + folder + c.scene + ".pbtxt");
  std::vector<std::string> args = short_cut(c.threads, c.transport);
  args.insert(args.end(), c.sets.begin(), c.sets.end());
  std::string name = c.scene + c.tag + "_" + c.threads + "_" + c.transport;
  std::replace(name.begin(), name.end(), '/', '_');
  const fs::path dir = fresh_dir("restart_" + name);
  const std::vector<std::string> transport = {"--transport", c.transport};

  // A: straight through.
  const CouplerRun a = run_coupler(scene, args, dir / "a", 120000ms);
  ASSERT_EQ(a.code, 0) << a.err;

  // B: SIGTERM after the first checkpoint: it checkpoints again, stops, and is resumed; the
  // resumed run is stopped again after its next checkpoint and resumed once more.
  const fs::path b = dir / "b";
  ASSERT_EQ(run_until_checkpoints(scene, args, dir, b, 1, SIGTERM, "b"), 128 + SIGTERM);
  EXPECT_EQ(text(coupler::read_summary(b / "summary.json"), "status"), "interrupted");
  {
    std::vector<std::string> argv = {bin("coupler"), "resume", b.string(), "--transport",
                                     c.transport};
    const Spawned s = spawn(argv, dir, "b_resume_1");
    KillOnExit guard{s.pid};
    const std::size_t before = checkpoints(b).size();
    const std::string newest = checkpoints(b).back().filename().string();
    while (checkpoints(b).back().filename().string() == newest) {
      if (wait_exit(s.pid, 10ms)) break;
    }
    kill(s.pid, SIGTERM);
    const int code = wait_exit(s.pid, 60s).value_or(-1);
    EXPECT_TRUE(code == 128 + SIGTERM || code == 0) << code;
    EXPECT_GE(checkpoints(b).size(), std::min<std::size_t>(before, 2));
  }
  std::string err;
  ASSERT_EQ(resume(b, transport, dir, "b_resume_2", &err), 0) << err;
  expect_same_output(dir / "a" / "out", b, "SIGTERM, resumed twice");

  // C: SIGKILL after the second checkpoint: no checkpoint of its own; resumed from the last one.
  const fs::path cdir = dir / "c";
  ASSERT_EQ(run_until_checkpoints(scene, args, dir, cdir, 2, SIGKILL, "c"), 128 + SIGKILL);
  ASSERT_EQ(resume(cdir, transport, dir, "c_resume", &err), 0) << err;
  expect_same_output(dir / "a" / "out", cdir, "SIGKILL, resumed");
}

INSTANTIATE_TEST_SUITE_P(
    Cuts, Restart,
    ::testing::Values(Case{"dry_reduced", "1", "ipc"}, Case{"dry_reduced", "2", "inproc"},
                      Case{"saturated_reduced", "1", "ipc"}, Case{"saturated_reduced", "1", "inproc"},
                      Case{"saturated_reduced", "2", "ipc"}, Case{"saturated_reduced", "2", "inproc"},
                      // Dashpots, a held base, rolling springs (whose moments are state) and
                      // softening bonds (damaged from 2.7 ms, after the resumes: the damage's
                      // own save and load is tests/dem/bond_softening_test.cpp's).
                      Case{"dry_reduced_long", "2", "ipc",
                           {"--set", "dem.contact.rolling_friction=0.1", "--set",
                            "dem.bonds.softening_ratio=9"},
                           "_rolling_softening"},
                      // ... and the open water's drag, whose work since the start is state.
                      Case{"saturated_reduced_long_viscous", "1", "inproc",
                           {"--set", "dem.contact.rolling_friction=0.1", "--set",
                            "fluid.open_water_drag=true"},
                           "_rolling_drag"},
                      // The dynamic scene's fluid force, extrapolated between exchanges at
                      // N = 8 with the lag's energy taken out: its line through the last two
                      // exchanges and the observer's residuals are state (the case above runs
                      // it too, on one thread and inproc).
                      Case{"saturated_reduced_long_viscous", "2", "ipc"},
                      // ... and with each grain's own fluid stiffness between exchanges: K_ii,
                      // x^m and t_m of the last exchange are state.
                      Case{"saturated_reduced_long_viscous", "2", "ipc",
                           {"--set", "coupling.fluid_stiffness=self"}, "_self_stiffness"},
                      // The pore fluid on points of about four grains (its clusters are
                      // rebuilt from the scene, its state is the points').
                      Case{"saturated_reduced_long_viscous", "2", "ipc",
                           {"--set", "fluid.point_spacing=2"}, "_points"},
                      // Servo-steered side walls and the biaxial summary's samples, over the
                      // failure peak (at about 1.9 ms), on a specimen half as wide and high.
                      Case{"calibration/biaxial", "2", "ipc",
                           {"--set", "dem.specimen.width_m=0.0125", "--set",
                            "dem.specimen.height_m=0.025", "--set", "time.end_time_s=0.0025"},
                           "_small"},
                      // The fracture test's summary (the pull's drop and the ends' work since)
                      // across its peak (0.4 ms) and drop, on softening bonds.
                      Case{"calibration/fracture", "1", "ipc",
                           {"--set", "dem.specimen.width_m=0.02", "--set",
                            "dem.specimen.height_m=0.01", "--set",
                            "dem.loading_test.platen_speed_m_s=0.02", "--set",
                            "dem.bonds.softening_ratio=9", "--set", "dem.damping.model=viscous",
                            "--set", "dem.damping.damping_ratio=0.005", "--set",
                            "time.end_time_s=0.0025"},
                           "_small_softening"}),
    [](const ::testing::TestParamInfo<Case>& info) {
      std::string scene = info.param.scene;
      std::replace(scene.begin(), scene.end(), '/', '_');
      return scene + info.param.tag + "_" + info.param.threads + "threads_" +
             info.param.transport;
    });

// SIGUSR1 (a scheduler's warning before the time limit) writes a checkpoint and the run carries
// on to the same result.
TEST(Restart, SigUsr1WritesACheckpointAndTheRunCarriesOn) {
  const std::string scene = source("cases/cutting/dry_reduced.pbtxt");
  const fs::path dir = fresh_dir("restart_usr1");
  const std::vector<std::string> args = {"--set", "time.end_time_s=0.004", "--set",
                                         "output.frame_interval_s=0.001"};
  const CouplerRun a = run_coupler(scene, args, dir / "a", 120000ms);
  ASSERT_EQ(a.code, 0) << a.err;
  const fs::path out = dir / "u";
  std::vector<std::string> argv = {bin("coupler"), "run", scene, "--out", out.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  const Spawned s = spawn(argv, dir, "usr1");
  KillOnExit guard{s.pid};
  // run.h5 exists once the loop is about to start: the handlers are in place by then.
  while (!fs::exists(out / "run.h5")) {
    ASSERT_FALSE(wait_exit(s.pid, 5ms).has_value()) << "the run ended before its run.h5 appeared";
  }
  kill(s.pid, SIGUSR1);
  ASSERT_EQ(wait_exit(s.pid, 120s).value_or(-1), 0);
  const std::string err = read_file(s.err_file);
  EXPECT_NE(err.find("checkpoint  SIGUSR1 at"), std::string::npos) << err;
  EXPECT_EQ(checkpoints(out).size(), 2u) << "SIGUSR1's and the end of the run's";
  const H5Reader ha(a.out / "run.h5"), hu(out / "run.h5");
  EXPECT_TRUE(bit_identical(ha.doubles("/timeseries/tool_force_x_n_per_m"),
                            hu.doubles("/timeseries/tool_force_x_n_per_m")));
  EXPECT_TRUE(bit_identical(ha.doubles(last_frame(ha) + "/position"),
                            hu.doubles(last_frame(hu) + "/position")));
}

// A finished run continued to a later end time writes what a run to that end time writes: its
// end-of-run checkpoint was taken before the last exchange, which the end cut short.
class Extend : public ::testing::TestWithParam<std::string> {};

TEST_P(Extend, AFinishedRunContinuedToALaterEndTimeMatchesALongerRun) {
  const std::string scene = source("cases/cutting/" + GetParam() + ".pbtxt");
  const fs::path dir = fresh_dir("restart_extend_" + GetParam());
  std::vector<std::string> args = short_cut("1", "ipc");
  const CouplerRun a = run_coupler(scene, args, dir / "a", 120000ms);
  ASSERT_EQ(a.code, 0) << a.err;
  args.insert(args.end(), {"--set", "time.end_time_s=0.0025"});
  const CouplerRun b = run_coupler(scene, args, dir / "b", 120000ms);
  ASSERT_EQ(b.code, 0) << b.err;
  std::string err;
  // How the run uses the cores may change on resume; the overlap and the fluid's thread count
  // change no bit (a scene without a `coupling` block gains one here, which is no difference).
  std::vector<std::string> resume_args = {"--set", "time.end_time_s=0.004", "--set",
                                          "coupling.overlap=off"};
  if (GetParam() != "dry_reduced") resume_args.insert(resume_args.end(), {"--set", "fluid.threads=2"});
  ASSERT_EQ(resume(b.out, resume_args, dir, "extend", &err), 0) << err;
  EXPECT_NE(err.find("changed time.end_time_s: 0.0025 -> 0.004"), std::string::npos) << err;
  EXPECT_NE(err.find("changed coupling.overlap: (default) -> \"off\""), std::string::npos) << err;
  expect_same_output(a.out, b.out, "extended");
}

TEST(Restart, ADryRunResumedWithAFluidSettingIsRefused) {
  // fluid.threads may change on resume, but on a dry run it would add a fluid: refused.
  const std::string scene = source("cases/cutting/dry_reduced.pbtxt");
  const fs::path dir = fresh_dir("restart_dry_fluid");
  std::vector<std::string> args = short_cut("1", "ipc");
  args.insert(args.end(), {"--set", "time.end_time_s=0.001"});
  const CouplerRun r = run_coupler(scene, args, dir / "r", 120000ms);
  ASSERT_EQ(r.code, 0) << r.err;
  std::string err;
  EXPECT_EQ(resume(r.out, {"--set", "time.end_time_s=0.002", "--set", "fluid.threads=2"}, dir,
                   "dry_fluid", &err),
            kExitBadInput)
      << err;
  EXPECT_NE(err.find("fluid"), std::string::npos) << err;
}

INSTANTIATE_TEST_SUITE_P(Cuts, Extend, ::testing::Values("dry_reduced", "saturated_reduced"));

// What a resume refuses, and that a refusal changes nothing.
TEST(Restart, ResumeRefusesACheckpointOfAnotherRun) {
  // `coupler resume OUT` takes its scene from the checkpoint, so a checkpoint copied in from
  // another run (here one with another friction, run further, so it is the newest) matched only
  // itself and was continued. The run's own scene is the one OUT/run.h5 was written with: the
  // foreign checkpoint is refused naming the field, the run falls back to its own; with none of
  // its own, nothing is resumed and nothing in OUT changes.
  const std::string scene = source("cases/cutting/dry_reduced.pbtxt");
  const fs::path dir = fresh_dir("restart_foreign");
  std::vector<std::string> args = short_cut("1", "ipc");
  args.insert(args.end(), {"--set", "time.end_time_s=0.001"});
  const CouplerRun own = run_coupler(scene, args, dir / "own", 120000ms);
  ASSERT_EQ(own.code, 0) << own.err;
  std::vector<std::string> other_args = short_cut("1", "ipc");
  other_args.insert(other_args.end(),
                    {"--set", "time.end_time_s=0.002", "--set", "dem.contact.friction=0.5"});
  const CouplerRun other = run_coupler(scene, other_args, dir / "other", 120000ms);
  ASSERT_EQ(other.code, 0) << other.err;
  const fs::path foreign = checkpoints(other.out).back();
  fs::copy_file(foreign, own.out / "checkpoints" / foreign.filename());
  ASSERT_EQ(checkpoints(own.out).back().filename(), foreign.filename());

  std::string err;
  EXPECT_EQ(resume(own.out, {}, dir, "foreign_fallback", &err), 0) << err;
  EXPECT_NE(err.find("belongs to another run"), std::string::npos) << err;
  EXPECT_NE(err.find("friction"), std::string::npos) << err;
  EXPECT_NE(err.find("resume     from"), std::string::npos) << err;

  for (const fs::path& f : checkpoints(own.out)) {
    if (f.filename() != foreign.filename()) fs::remove(f);
  }
  const std::string h5_before = read_file(own.out / "run.h5");
  EXPECT_EQ(resume(own.out, {}, dir, "foreign_only", &err), kExitBadInput) << err;
  EXPECT_NE(err.find("friction"), std::string::npos) << err;
  EXPECT_NE(err.find("no usable checkpoint; nothing in it was changed"), std::string::npos) << err;
  EXPECT_EQ(read_file(own.out / "run.h5"), h5_before) << "a refused resume touched run.h5";
}

TEST(Restart, RefusesChangedScenesAndBadCheckpointsAndFallsBackToTheLastGoodOne) {
  const std::string scene = source("cases/cutting/dry_reduced.pbtxt");
  const fs::path dir = fresh_dir("restart_refusals");
  std::vector<std::string> args = short_cut("1", "ipc");
  args.insert(args.end(), {"--set", "time.end_time_s=0.002", "--set",
                           "output.checkpoints_kept=3"});
  const CouplerRun r = run_coupler(scene, args, dir / "r", 120000ms);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto files = checkpoints(r.out);
  ASSERT_EQ(files.size(), 3u);  // kept: the two newest interval ones and the end of the run
  const std::string h5_before = read_file(r.out / "run.h5");

  // Nothing to resume from.
  std::string err;
  EXPECT_EQ(resume(dir / "nowhere", {}, dir, "none", &err), kExitBadInput);
  EXPECT_NE(err.find("no checkpoint to resume from"), std::string::npos) << err;

  // A physics field changed through --set: refused by every checkpoint, naming the field.
  EXPECT_EQ(resume(r.out, {"--set", "dem.damping.local_coefficient=0.5"}, dir, "physics", &err),
            kExitBadInput);
  EXPECT_NE(err.find("local_coefficient"), std::string::npos) << err;
  EXPECT_NE(err.find("no usable checkpoint; nothing in it was changed"), std::string::npos) << err;

  // `coupler run --resume` with a scene whose physics differs from the checkpoint's.
  std::vector<std::string> changed = args;
  changed.insert(changed.end(), {"--set", "dem.contact.friction=0.1", "--resume"});
  const CouplerRun refused = run_coupler(scene, changed, dir / "r", 120000ms);
  EXPECT_EQ(refused.code, kExitBadInput) << refused.err;
  EXPECT_NE(refused.err.find("friction"), std::string::npos) << refused.err;
  EXPECT_EQ(read_file(r.out / "run.h5"), h5_before) << "a refused resume touched run.h5";

  // The newest checkpoint corrupted (64 bytes in its middle, where the particle arrays lie,
  // overwritten), the one before truncated: both refused with their reason, and the run
  // continues from the oldest.
  {
    std::string bytes = read_file(files[2]);
    for (std::size_t k = 0; k < 64; ++k) bytes[bytes.size() / 2 + k] ^= 0x5a;
    std::ofstream(files[2], std::ios::binary | std::ios::trunc) << bytes;
    const std::string half = read_file(files[1]).substr(0, 3000);
    std::ofstream(files[1], std::ios::binary | std::ios::trunc) << half;
  }
  EXPECT_EQ(resume(r.out, {"--set", "time.end_time_s=0.003"}, dir, "fallback", &err), 0) << err;
  EXPECT_NE(err.find(files[2].filename().string() + ": refused"), std::string::npos) << err;
  EXPECT_NE(err.find(files[1].filename().string() + ": refused"), std::string::npos) << err;
  EXPECT_NE(err.find("resume     from " + files[0].string()), std::string::npos) << err;
}

}  // namespace
}  // namespace rockcut::test
