#include "integration/process_helpers.hpp"

#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <thread>

namespace rockcut::test {

namespace fs = std::filesystem;

KillOnExit::~KillOnExit() {
  if (pid > 0 && kill(pid, 0) == 0) {
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
}

Spawned spawn(const std::vector<std::string>& argv, const fs::path& dir, const std::string& tag,
              int stdout_fd) {
  Spawned s;
  fs::create_directories(dir);
  s.out_file = dir / (tag + ".stdout");
  s.err_file = dir / (tag + ".stderr");
  std::vector<std::string> storage = argv;
  std::vector<char*> args;
  for (auto& a : storage) args.push_back(a.data());
  args.push_back(nullptr);
  s.pid = fork();
  if (s.pid == 0) {
    const int out =
        stdout_fd >= 0 ? stdout_fd : open(s.out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(s.err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, 1);
    dup2(err, 2);
    execv(args[0], args.data());
    _exit(127);
  }
  return s;
}

std::optional<int> wait_exit(pid_t pid, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {
      if (WIFEXITED(status)) return WEXITSTATUS(status);
      if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
      return -1;
    }
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

int run(const std::vector<std::string>& argv, const fs::path& dir, const std::string& tag,
        std::string* out, std::string* err, std::chrono::milliseconds timeout) {
  const Spawned s = spawn(argv, dir, tag);
  auto code = wait_exit(s.pid, timeout);
  if (!code) {
    kill(s.pid, SIGKILL);
    waitpid(s.pid, nullptr, 0);
    code = -9999;
  }
  if (out) *out = read_file(s.out_file);
  if (err) *err = read_file(s.err_file);
  return *code;
}

std::vector<pid_t> children_of(pid_t pid) {
  std::vector<pid_t> kids;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    // Fields after the ")" that closes the command: state ppid ...
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state = 0;
    pid_t ppid = 0;
    rest >> state >> ppid;
    if (ppid == pid && state != 'Z') kids.push_back(std::stoi(name));
  }
  return kids;
}

pid_t wait_for_child_named(pid_t pid, const std::string& name, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    for (pid_t kid : children_of(pid)) {
      if (command_name(kid) == name) return kid;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return -1;
}

bool is_gone(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;
  const auto close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'Z';
}

std::string command_name(pid_t pid) {
  std::ifstream comm("/proc/" + std::to_string(pid) + "/comm");
  std::string name;
  std::getline(comm, name);
  return name;
}

std::string read_file(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int free_tcp_port() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  socklen_t len = sizeof addr;
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  const int port = ntohs(addr.sin_port);
  close(fd);
  return port;
}

std::string bin(const std::string& name) { return std::string(ROCKCUT_BIN_DIR) + "/" + name; }

std::string source(const std::string& relative) {
  return std::string(ROCKCUT_SOURCE_DIR) + "/" + relative;
}

fs::path fresh_dir(const std::string& name) {
  // ctest runs tests in parallel: the test's own name keeps their directories apart.
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string owner = test ? std::string(test->test_suite_name()) + "." + test->name() : "";
  std::string unique = owner + "/" + name;
  std::replace(unique.begin(), unique.end(), '/', '_');
  const fs::path dir = fs::path(ROCKCUT_TEST_TMP) / "integration" / unique;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

CouplerRun run_coupler(const std::string& scene, const std::vector<std::string>& args,
                       const fs::path& dir, std::chrono::milliseconds timeout) {
  std::vector<std::string> argv = {bin("coupler"), "run", scene, "--out", (dir / "out").string()};
  argv.insert(argv.end(), args.begin(), args.end());
  CouplerRun r;
  r.out = dir / "out";
  r.code = run(argv, dir, "coupler", &r.out_text, &r.err, timeout);
  return r;
}

}  // namespace rockcut::test
