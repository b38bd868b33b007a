// One run at a time in an output directory: an exclusive lock (flock) on OUT/.rockcut.lock, held
// for the whole run and released by the kernel when the coupler ends in any way (also SIGKILL).
// A second run started into the same directory is refused at once, naming the first one's pid.
// The lock file goes at the end, and with it the directory if the run created it and wrote
// nothing else (a refused scene leaves no trace).
#pragma once

#include <filesystem>
#include <stdexcept>

namespace rockcut::coupler {

class OutDirLock {
 public:
  /// Creates `out_dir` if needed and takes its lock; throws std::runtime_error naming the other
  /// run's pid if another coupler holds it, or why the lock cannot be taken.
  explicit OutDirLock(const std::filesystem::path& out_dir);
  ~OutDirLock();
  OutDirLock(const OutDirLock&) = delete;
  OutDirLock& operator=(const OutDirLock&) = delete;

 private:
  int fd_ = -1;
  std::filesystem::path dir_, file_;
  bool created_dir_ = false;
};

}  // namespace rockcut::coupler
