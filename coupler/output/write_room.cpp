#include "output/write_room.hpp"

#include <sys/resource.h>
#include <sys/statvfs.h>

#include <algorithm>

namespace rockcut::coupler {

std::optional<std::string> lacks_room(const std::filesystem::path& file,
                                      std::uint64_t allocated_bytes, std::uint64_t on_disk_bytes,
                                      std::uint64_t more_bytes, std::uint64_t reserve_bytes) {
  const std::uint64_t needed = more_bytes + reserve_bytes;
  rlimit limit{};
  if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      allocated_bytes + needed > limit.rlim_cur) {
    return "the file-size limit (ulimit -f) of " + std::to_string(limit.rlim_cur) + " bytes leaves " +
           file.filename().string() + " (" + std::to_string(allocated_bytes) +
           " bytes) no room for the next " + std::to_string(more_bytes) +
           " bytes and its close; nothing of it was written";
  }
  struct statvfs fs{};
  if (statvfs(file.parent_path().c_str(), &fs) == 0) {
    const std::uint64_t free_bytes = static_cast<std::uint64_t>(fs.f_bavail) * fs.f_frsize;
    // Bytes the library has allocated but not yet written still take disk space.
    const std::uint64_t pending = allocated_bytes - std::min(allocated_bytes, on_disk_bytes);
    if (pending + needed > free_bytes) {
      return "the file system of " + file.parent_path().string() + " has " +
             std::to_string(free_bytes) + " bytes free, too few for the next " +
             std::to_string(more_bytes) + " bytes of " + file.filename().string() +
             " and its close (disk full?); nothing of it was written";
    }
  }
  return std::nullopt;
}

}  // namespace rockcut::coupler
