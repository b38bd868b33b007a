// Launching the real executables from tests: spawn with output captured to files, wait with a
// deadline, find a process's children, tell whether a pid is gone.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rockcut::test {

struct Spawned {
  pid_t pid = -1;
  std::filesystem::path out_file, err_file;
};

/// Kills (SIGKILL) and reaps the process when the scope ends if it is still running, so a failing
/// test leaves nothing behind.
struct KillOnExit {
  pid_t pid;
  ~KillOnExit();
};

/// Starts `argv` (argv[0] is the program path) with stdout/stderr into files under `dir`; with
/// `stdout_fd` >= 0, stdout goes to that descriptor instead (open it close-on-exec, so that the
/// child keeps only its own copy).
Spawned spawn(const std::vector<std::string>& argv, const std::filesystem::path& dir,
              const std::string& tag, int stdout_fd = -1);

/// Waits for `pid`; returns its exit code (128 + signal if killed), or nullopt on timeout.
std::optional<int> wait_exit(pid_t pid, std::chrono::milliseconds timeout);

/// Runs to completion (with a deadline; the process is killed after it) and returns the exit code.
int run(const std::vector<std::string>& argv, const std::filesystem::path& dir,
        const std::string& tag, std::string* out = nullptr, std::string* err = nullptr,
        std::chrono::milliseconds timeout = std::chrono::milliseconds(120000));

/// What `coupler run` left: its output directory, exit code and stderr.
struct CouplerRun {
  std::filesystem::path out;
  int code = -1;
  std::string err;
  std::string out_text;  ///< what it printed on stdout
};

/// Runs `coupler run SCENE --out DIR/out ARGS...` in `dir` to completion (killed after `timeout`).
CouplerRun run_coupler(const std::string& scene, const std::vector<std::string>& args,
                       const std::filesystem::path& dir, std::chrono::milliseconds timeout);

/// Direct children of `pid` (from /proc).
std::vector<pid_t> children_of(pid_t pid);
/// Waits until `pid` has a child whose command name is `name` (one that has exec'ed: between fork
/// and exec a child still carries its parent's name); returns it, or -1 on timeout.
pid_t wait_for_child_named(pid_t pid, const std::string& name, std::chrono::milliseconds timeout);
/// True if no live (non-zombie) process has this pid.
bool is_gone(pid_t pid);
/// The command name of `pid` (/proc/pid/comm), or "".
std::string command_name(pid_t pid);

std::string read_file(const std::filesystem::path& file);
/// A loopback TCP port that was free a moment ago.
int free_tcp_port();

/// ROCKCUT_BIN_DIR / name
std::string bin(const std::string& name);
/// ROCKCUT_SOURCE_DIR / relative
std::string source(const std::string& relative);
/// A fresh directory under ROCKCUT_TEST_TMP, unique to the running test and `name`.
std::filesystem::path fresh_dir(const std::string& name);

}  // namespace rockcut::test
