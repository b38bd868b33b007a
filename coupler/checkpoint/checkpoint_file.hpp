// A checkpoint: one self-describing HDF5 file OUT/checkpoints/checkpoint_<step>.h5 holding the
// coupler's and each module's state (opaque named arrays, wire/state_archive.hpp), the effective
// scene text, the program and protocol versions, the step and time, and a checksum over all of it.
// Written atomically (temporary file, fsync, rename, fsync of the directory): a checkpoint file
// that exists under its final name is whole.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "run/checkpoint_values.hpp"

namespace rockcut::coupler {

/// The file name of the checkpoint at `step` (sorting by name sorts by step).
std::string checkpoint_file_name(std::uint64_t step);

/// Writes `checkpoint` into `dir` (created if missing) atomically; returns the file's path.
std::filesystem::path write_checkpoint(const std::filesystem::path& dir, const Checkpoint& checkpoint);

/// Reads and verifies a checkpoint file. Throws CheckpointError naming the reason: not HDF5 or
/// truncated, not a rockcut checkpoint, a member missing, or a checksum that does not match.
Checkpoint read_checkpoint(const std::filesystem::path& file);

/// The checkpoint files in `dir`, newest (highest step) first; none if `dir` does not exist.
std::vector<std::filesystem::path> list_checkpoints(const std::filesystem::path& dir);

/// Removes all but the newest `keep` checkpoints of `dir` (and temporary files left by a writer
/// that was killed).
void prune_checkpoints(const std::filesystem::path& dir, unsigned keep);

/// FNV-1a 64 over the checkpoint's header and every part's arrays and texts, in name order.
std::uint64_t checkpoint_checksum(const Checkpoint& checkpoint);

}  // namespace rockcut::coupler
