// A run killed without close() must leave run.h5 and run.xdmf readable up to the last frame.
//
// Why fork: inside one process HDF5 shares an already-open file between handles, so a second
// H5Fopen would read the writer's in-memory cache and prove nothing about the bytes on disk.
// Here a child process writes and then dies by SIGKILL (no destructors, no atexit handlers, no
// HDF5 library shutdown); the parent, which never had the file open, reads what is on disk.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "output/h5_handle.hpp"
#include "output/run_file.hpp"

namespace rockcut::coupler::testing {
// Defined in h5_read_util.cpp.
std::filesystem::path scratch_dir(const std::string& name);
h5::Handle open_read_only(const std::filesystem::path& file);
std::vector<hsize_t> dataset_dims(hid_t file, const std::string& path);
std::vector<double> read_doubles(hid_t file, const std::string& path);
std::string read_string_attribute(hid_t loc, const std::string& name);
double read_double_attribute(hid_t loc, const std::string& name);

namespace {

constexpr std::size_t kCrashParticles = 4;
constexpr int kFrames = 3;
constexpr int kRowsPerFrame = 5;

std::vector<double> frame_positions(int frame) {
  std::vector<double> xy(2 * kCrashParticles);
  for (std::size_t i = 0; i < xy.size(); ++i) xy[i] = frame * 100.0 + static_cast<double>(i);
  return xy;
}

double row_value(int row) { return 0.5 * row; }

/// The child: writes rows and frames, one more unflushed row, then is killed mid-run.
[[noreturn]] void run_child_and_die(const std::filesystem::path& dir) {
  try {
    RunFile run(dir, "crash scene", {{"status", "running"}});
    int row = 0;
    for (int f = 0; f < kFrames; ++f) {
      for (int k = 0; k < kRowsPerFrame; ++k, ++row) {
        run.append_timeseries(row * 1e-3, static_cast<std::uint64_t>(row),
                              {{"force", row_value(row)}});
      }
      const std::vector<double> xy = frame_positions(f);
      run.write_frame(f * 0.1, static_cast<std::uint64_t>(row), kCrashParticles,
                      {{"position", 2, xy}});
    }
    run.append_timeseries(1.0, 999, {{"force", -1.0}});  // after the last flush
    raise(SIGKILL);  // the crash: `run` is never closed or destroyed
  } catch (...) {
  }
  _exit(3);  // reached only if writing failed; the parent sees a normal exit and fails
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::size_t count_of(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

TEST(RunFileCrash, FramesWrittenBeforeAKillStayReadable) {
  const auto dir = scratch_dir("crash");
  std::fflush(nullptr);  // don't let the child re-emit buffered test output
  const pid_t pid = fork();
  ASSERT_GE(pid, 0) << "fork failed";
  if (pid == 0) run_child_and_die(dir);

  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child exited normally (status " << status
                                   << "): writing failed before the simulated crash";
  ASSERT_EQ(WTERMSIG(status), SIGKILL);

  // The file was never closed, yet it opens and holds every flushed frame bit for bit.
  h5::Handle file = open_read_only(dir / "run.h5");
  EXPECT_EQ(read_string_attribute(file.get(), "scene"), "crash scene");
  EXPECT_EQ(read_string_attribute(file.get(), "status"), "running");
  for (int f = 0; f < kFrames; ++f) {
    const std::string group = "/frames/00000" + std::to_string(f);
    SCOPED_TRACE(group);
    EXPECT_EQ(read_doubles(file.get(), group + "/position"), frame_positions(f));
    h5::Handle g = h5::group(H5Gopen2(file.get(), group.c_str(), H5P_DEFAULT), group, "open");
    EXPECT_EQ(read_double_attribute(g.get(), "time_s"), f * 0.1);
  }
  // Rows appended before the last frame were flushed with it; the one after may or may not be.
  const std::size_t flushed_rows = kFrames * kRowsPerFrame;
  const std::vector<double> force = read_doubles(file.get(), "/timeseries/force");
  ASSERT_GE(force.size(), flushed_rows);
  ASSERT_LE(force.size(), flushed_rows + 1);
  for (std::size_t i = 0; i < flushed_rows; ++i) {
    EXPECT_EQ(force[i], row_value(static_cast<int>(i))) << "row " << i;
  }
  EXPECT_EQ(read_doubles(file.get(), "/timeseries/time_s").size(), force.size());

  // The XDMF index lists exactly the frames on disk and was never left half-written.
  const std::string xdmf = read_text(dir / "run.xdmf");
  EXPECT_EQ(count_of(xdmf, "GridType=\"Uniform\""), static_cast<std::size_t>(kFrames));
  EXPECT_NE(xdmf.find("run.h5:/frames/000002/position"), std::string::npos);
  EXPECT_NE(xdmf.find("</Xdmf>"), std::string::npos);
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << entry.path();
  }
}

}  // namespace
}  // namespace rockcut::coupler::testing
