#include "run/ipc_directory.hpp"

#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

namespace rockcut::coupler {

namespace {

namespace fs = std::filesystem;

// The private socket directories of couplers that were killed (SIGKILL leaves no chance to clean
// up): this user's rockcut-XXXXXX directories in `base` whose coupler.pid names a process that is
// gone.
void remove_orphaned_ipc_directories(const fs::path& base) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(base, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("rockcut-", 0) != 0 || name.size() != 14 || !entry.is_directory(ec)) continue;
    struct stat info {};
    if (::lstat(entry.path().c_str(), &info) != 0 || info.st_uid != ::getuid()) continue;
    std::ifstream pid_file(entry.path() / "coupler.pid");
    long pid = 0;
    if (!(pid_file >> pid) || pid <= 0) continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) fs::remove_all(entry.path(), ec);
  }
}

}  // namespace

fs::path make_private_ipc_directory() {
  constexpr std::size_t kMaxSocketPath = 100;
  // TMPDIR that names nothing or a file makes temp_directory_path() throw a bare
  // filesystem_error: say what is wrong and what to do instead.
  std::error_code tmp_error;
  fs::path base = fs::temp_directory_path(tmp_error);
  if (tmp_error) {
    const char* tmpdir = std::getenv("TMPDIR");
    throw EnvironmentError(std::string("TMPDIR=") + (tmpdir ? tmpdir : "") +
                             " is not a directory (" + tmp_error.message() +
                             "): the module sockets need a private directory there; set TMPDIR "
                             "to a writable directory or unset it");
  }
  if ((base / "rockcut-XXXXXX" / "fluid.sock").string().size() > kMaxSocketPath) base = "/tmp";
  remove_orphaned_ipc_directories(base);
  std::string templ = (base / "rockcut-XXXXXX").string();
  if (!mkdtemp(templ.data())) {
    throw EnvironmentError("cannot create a private directory for the module sockets in " +
                             base.string() + ": " + std::strerror(errno) +
                             " (set TMPDIR to a writable directory)");
  }
  const fs::path dir = templ;
  // Who owns it: a coupler killed by SIGKILL cannot remove it, the next run does.
  std::ofstream(dir / "coupler.pid") << getpid() << "\n";
  return dir;
}

}  // namespace rockcut::coupler
