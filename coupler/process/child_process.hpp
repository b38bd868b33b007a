// A module started as a child process. It is killed if the coupler dies (PR_SET_PDEATHSIG), so no
// run leaves an orphan behind, whatever stops the coupler.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rockcut::coupler {

class ChildProcess {
 public:
  /// Starts `executable` with `args`. Throws std::runtime_error if it cannot be started.
  ChildProcess(const std::filesystem::path& executable, const std::vector<std::string>& args);
  /// Kills the process if it is still running, and reaps it.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  /// If the process has ended: how, e.g. "exited with status 3" or "was killed by signal 9
  /// (SIGKILL)". Never blocks.
  std::optional<std::string> ended();
  /// Waits up to `grace` for a voluntary exit, then SIGTERM, then SIGKILL. Reaps the process.
  void stop(std::chrono::milliseconds grace);

 private:
  bool wait_for(std::chrono::milliseconds timeout);
  pid_t pid_ = -1;
  std::optional<std::string> ended_;
};

}  // namespace rockcut::coupler
