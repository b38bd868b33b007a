// What a checkpoint carries: the coupler's and each module's state as named values
// (wire/state_archive.hpp), the effective scene, the versions, the step and the time. The run
// state of the bottom floor; the file that holds it is checkpoint/checkpoint_file.hpp.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "wire/state_archive.hpp"

namespace rockcut::coupler {

/// A checkpoint that cannot be used; what() is the reason (the caller names the file).
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Checkpoint {
  std::string rockcut_version;
  std::uint32_t protocol_version = 0;
  std::string scene_text;   ///< the effective scene (after overrides), as in run.h5
  std::string scene_path;   ///< where the scene was read from
  std::vector<std::string> overrides;  ///< the --set arguments of the run
  std::uint64_t step = 0;
  double time_s = 0.0;
  /// "coupler", "dem", "fluid": each part's state.
  std::map<std::string, state::StateArchive> parts;
};

}  // namespace rockcut::coupler
