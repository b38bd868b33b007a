// Room for run.h5 to grow, checked before it does: an HDF5 file whose write fails half way (a
// full disk, a file-size limit) cannot be opened again, so every frame written before would be
// lost. A write that would not fit is never started; the run stops with what it wrote flushed
// and the file closable (exit 5).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace rockcut::coupler {

/// Bytes kept free beyond every write: what closing the file and the run's status attributes
/// need (metadata the library flushes at close), with room to spare.
inline constexpr std::uint64_t kCloseReserveBytes = 64 * 1024;

/// Why `more_bytes` cannot be added to `file`, which has `allocated_bytes` allocated (written or
/// promised to the library) of which `on_disk_bytes` are on disk: the process's file-size limit
/// (RLIMIT_FSIZE, `ulimit -f`) or the free space of the file system (statvfs) leaves less than
/// `more_bytes` + `reserve_bytes`. None where it fits (or the limits cannot be read). The status
/// attributes written as a run stops may use most of the reserve.
std::optional<std::string> lacks_room(const std::filesystem::path& file,
                                      std::uint64_t allocated_bytes, std::uint64_t on_disk_bytes,
                                      std::uint64_t more_bytes,
                                      std::uint64_t reserve_bytes = kCloseReserveBytes);

}  // namespace rockcut::coupler
