#include "process/child_process.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace rockcut::coupler {

namespace {

std::string describe(int status) {
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* abbrev = sigabbrev_np(sig);
    return "was killed by signal " + std::to_string(sig) +
           (abbrev ? std::string(" (SIG") + abbrev + ")" : std::string());
  }
  return "ended (status " + std::to_string(status) + ")";
}

}  // namespace

ChildProcess::ChildProcess(const std::filesystem::path& executable,
                           const std::vector<std::string>& args) {
  if (access(executable.c_str(), X_OK) != 0) {
    throw std::runtime_error("cannot run " + executable.string() + ": " + std::strerror(errno));
  }
  std::vector<std::string> argv_storage;
  argv_storage.push_back(executable.string());
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);

  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid_ == 0) {
    // Child: die with the coupler, whatever kills it; keep the terminal's SIGINT away so the coupler
    // alone decides how to shut down.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    setpgid(0, 0);
    signal(SIGINT, SIG_IGN);
    execv(argv[0], argv.data());
    _exit(127);
  }
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0 && !ended_) {
    kill(pid_, SIGKILL);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
}

std::optional<std::string> ChildProcess::ended() {
  if (ended_ || pid_ <= 0) return ended_;
  int status = 0;
  const pid_t r = waitpid(pid_, &status, WNOHANG);
  if (r == pid_) ended_ = describe(status);
  return ended_;
}

bool ChildProcess::wait_for(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!ended()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

void ChildProcess::stop(std::chrono::milliseconds grace) {
  if (pid_ <= 0 || ended()) return;
  if (wait_for(grace)) return;
  kill(pid_, SIGTERM);
  kill(pid_, SIGCONT);  // a stopped process cannot act on SIGTERM
  if (wait_for(std::chrono::milliseconds(500))) return;
  kill(pid_, SIGKILL);
  wait_for(std::chrono::milliseconds(2000));
}

}  // namespace rockcut::coupler
