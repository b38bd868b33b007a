#include "output/atomic_write.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

namespace rockcut::coupler {

namespace {

[[noreturn]] void fail_errno(const std::filesystem::path& file, const std::string& what, int err) {
  throw std::runtime_error(file.string() + ": " + what + ": " + std::strerror(err));
}

/// Owns a POSIX descriptor and, until released, the temporary file's name.
struct TempFile {
  std::filesystem::path path;
  int fd = -1;
  bool keep = false;
  ~TempFile() {
    if (fd >= 0) ::close(fd);
    if (!keep) {
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
    }
  }
};

}  // namespace

void write_file_atomically(const std::filesystem::path& target, std::string_view content) {
  // Same directory as the target so rename() stays within one file system (and is atomic);
  // the pid keeps two processes writing the same target from sharing a temporary.
  TempFile tmp;
  tmp.path = target;
  tmp.path += ".tmp." + std::to_string(::getpid());
  // A fresh file, never a link: whatever lies at the temporary's name (a planted symbolic link
  // to a file outside the output directory, a stale file) is unlinked, which removes a link and
  // not what it points to, and the file is then created exclusively without following links. A
  // name planted again between the two calls makes the open fail instead of writing through it.
  if (::unlink(tmp.path.c_str()) != 0 && errno != ENOENT) {
    fail_errno(tmp.path, "cannot remove what lies at the temporary file's name", errno);
  }
  tmp.fd = ::open(tmp.path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (tmp.fd < 0) fail_errno(tmp.path, "cannot create temporary file", errno);

  const char* data = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(tmp.fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail_errno(tmp.path, "cannot write", errno);
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  // fsync before rename: otherwise a power loss can leave the new name pointing at empty data.
  if (::fsync(tmp.fd) != 0) fail_errno(tmp.path, "cannot sync", errno);
  const int fd = tmp.fd;
  tmp.fd = -1;
  if (::close(fd) != 0) fail_errno(tmp.path, "cannot close", errno);
  if (::rename(tmp.path.c_str(), target.c_str()) != 0) {
    fail_errno(target, "cannot rename " + tmp.path.filename().string() + " over it", errno);
  }
  tmp.keep = true;
}

}  // namespace rockcut::coupler
