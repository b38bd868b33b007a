// The private directory of a run's ipc:// sockets.
#pragma once

#include <filesystem>
#include <stdexcept>

namespace rockcut::coupler {

/// The machine's set-up stops the run before any module starts (TMPDIR not a writable
/// directory): bad settings (exit code 2), not a module's failure.
class EnvironmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Creates a private directory (mkdtemp: mode 0700, other users stay off the sockets) under the
/// temporary directory, or under /tmp when TMPDIR is too long for a socket path (sockaddr_un holds
/// 108 bytes). It records the coupler's pid, and first removes the directories of couplers that
/// were killed (SIGKILL leaves them no chance to). Throws EnvironmentError naming the directory.
std::filesystem::path make_private_ipc_directory();

}  // namespace rockcut::coupler
