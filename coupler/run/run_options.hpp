// What `coupler run` and `coupler resume` are asked to do (the CLI's options), and the exit codes
// they answer with.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "run/module_link.hpp"

namespace rockcut::coupler {

/// Process exit codes of `coupler run`.
enum ExitCode : int {
  kExitOk = 0,
  kExitVerificationFailed = 1,
  kExitBadInput = 2,
  kExitModuleFailed = 3,
  kExitUnstable = 4,  ///< a runtime guard stopped the run (NaN, runaway kinetic energy, overlap)
  kExitOutputFailed = 5,  ///< the output could not be written (a full disk, a file-size limit)
};

struct RunOptions {
  std::filesystem::path scene_path;
  std::vector<std::string> overrides;  ///< --set path=value
  std::filesystem::path out_dir;       ///< empty: out/<scene file stem>
  Transport transport = Transport::ipc;
  std::string dem_endpoint = "tcp://127.0.0.1:5555";    ///< tcp only
  std::string fluid_endpoint = "tcp://127.0.0.1:5556";  ///< tcp only
  /// tcp only: key directory (wire/curve_keys.hpp) for CURVE sessions; empty: plain tcp.
  std::filesystem::path curve_keys;
  std::filesystem::path module_dir;    ///< where dem_module and fluid_module are (the coupler's dir)
  /// Wall time between two checkpoints [s]; 0: none on wall time.
  double checkpoint_every_s = 600.0;
  /// No checkpoint at all (nor at SIGUSR1, SIGTERM or the end): signals stop at once.
  bool no_checkpoints = false;
  /// `coupler resume OUT`: continue the run in out_dir from its newest valid checkpoint, with the
  /// scene the checkpoint holds (scene_path unused; `overrides` may change what cannot change
  /// the physics).
  bool resume = false;
  /// `coupler run CASE --resume`: as `resume` when out_dir holds a checkpoint, else a fresh run.
  bool resume_if_possible = false;
  /// A fresh run may replace the output of an earlier run in out_dir (else it is refused).
  bool overwrite = false;
};

}  // namespace rockcut::coupler
