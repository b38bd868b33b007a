#include "run/out_dir_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace rockcut::coupler {

OutDirLock::OutDirLock(const std::filesystem::path& out_dir) {
  std::error_code ec;
  dir_ = out_dir;
  created_dir_ = !std::filesystem::exists(out_dir, ec);
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    throw std::runtime_error("cannot create the output directory " + out_dir.string() + ": " +
                             ec.message());
  }
  const std::filesystem::path file = out_dir / ".rockcut.lock";
  file_ = file;
  // O_NOFOLLOW: a link planted in a shared directory is not followed; O_CLOEXEC: the modules do
  // not inherit (and so do not hold) the lock.
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error("cannot write in the output directory " + out_dir.string() + ": " +
                             std::strerror(errno));
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    char pid[32] = {};
    const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
    ::close(fd_);
    fd_ = -1;
    created_dir_ = false;  // the other run's directory
    std::string who = n > 0 ? std::string(pid, static_cast<std::size_t>(n)) : std::string("?");
    while (!who.empty() && (who.back() == '\n' || who.back() == ' ')) who.pop_back();
    throw std::runtime_error(out_dir.string() + " is in use by another run (coupler pid " + who +
                             "): wait for it to end, or choose another --out");
  }
  const std::string mine = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, mine.data(), mine.size(), 0) < 0) {
    // The lock holds regardless; only the pid shown to a second run is missing.
  }
}

OutDirLock::~OutDirLock() {
  if (fd_ < 0) return;
  std::error_code ec;
  std::filesystem::remove(file_, ec);  // while still holding the lock
  ::close(fd_);                        // releases it
  if (created_dir_ && std::filesystem::is_empty(dir_, ec)) std::filesystem::remove(dir_, ec);
}

}  // namespace rockcut::coupler
