#include "wire/shared_payload.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <system_error>
#include <unordered_map>

#include "wire/message.hpp"

namespace rockcut::wire {

namespace {

// The first 64 bytes of a segment; the values follow, so they are aligned for any SIMD load.
struct SegmentHeader {
  std::uint64_t magic;
  std::uint64_t generation;  // written last (release), read first (acquire)
  std::uint64_t bytes;       // of values in the last write (checked against the reader's header)
  std::uint64_t reserved[5];
};
static_assert(sizeof(SegmentHeader) == 64);
constexpr std::uint64_t kMagic = 0x314D485354554352ULL;  // "RCUTSHM1", little-endian

std::atomic<unsigned> arena_counter{0};

std::system_error shm_error(const std::string& what, const std::string& name) {
  return std::system_error(errno, std::generic_category(), what + " " + name);
}

// "/rockcut.12.0.position.1.v3" -> "/rockcut.12.0.position.1": one entry per segment in turn.
std::string slot_key(const std::string& name) {
  const std::size_t v = name.rfind(".v");
  return v == std::string::npos ? name : name.substr(0, v);
}

struct Mapping {
  std::string name;
  const void* base = nullptr;
  std::size_t size = 0;
  int fd = -1;                // kept open: every read checks the segment's size (fstat)
  std::uint64_t last_use = 0;
};

// Whether `name` follows a SharedPayloadArena's scheme for an array called `array`:
// "/rockcut.<pid>.<arena>-<clock>.<array>.<turn>.v<version>". Anything else (another program's
// /dev/shm object, a path) is not mapped.
bool follows_arena_scheme(const std::string& name, const std::string& array) {
  constexpr std::string_view kStart = "/rockcut.";
  if (name.size() > 255 || !name.starts_with(kStart) || array.empty() ||
      name.find('/', 1) != std::string::npos || array.find('/') != std::string::npos) {
    return false;
  }
  std::size_t k = kStart.size();
  const std::size_t pid_start = k;
  while (k < name.size() && name[k] >= '0' && name[k] <= '9') ++k;
  if (k == pid_start || k >= name.size() || name[k] != '.') return false;
  const std::size_t v = name.rfind(".v");
  if (v == std::string::npos || v + 2 == name.size()) return false;
  for (std::size_t i = v + 2; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') return false;
  }
  const std::string tail = "." + array + ".";  // then "0" or "1"
  return v >= tail.size() + 1 && (name[v - 1] == '0' || name[v - 1] == '1') &&
         name.compare(v - 1 - tail.size(), tail.size(), tail) == 0 && v - 1 - tail.size() > k;
}

void unmap(Mapping& m) {
  if (m.base) munmap(const_cast<void*>(m.base), m.size);
  if (m.fd >= 0) close(m.fd);
  m = {};
}

// The reader's mappings, one per segment in turn: a newer version of a segment replaces the
// older one (the sender unlinked it when the array outgrew it). At most kMaxMappings are kept:
// a peer naming ever new segments costs the least recently read one its mapping.
class MappingCache {
 public:
  static constexpr std::size_t kMaxMappings = 4 * Message::kMaxArrays;

  const Mapping& get(const std::string& name, const std::string& array) {
    std::lock_guard lock(mutex_);
    if (!follows_arena_scheme(name, array)) {
      throw ProtocolError("array '" + array + "': " + name.substr(0, 64) +
                          " is not a rockcut shared-memory segment of that array");
    }
    if (!by_slot_.contains(slot_key(name)) && by_slot_.size() >= kMaxMappings) evict_oldest();
    Mapping& m = by_slot_[slot_key(name)];
    m.last_use = ++uses_;
    if (m.name == name) return m;
    unmap(m);
    const int fd = shm_open(name.c_str(), O_RDONLY | O_NOFOLLOW, 0);
    if (fd < 0) {
      throw ProtocolError("shared-memory segment " + name + " cannot be opened: " +
                          std::strerror(errno));
    }
    struct stat st {};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) ||
        static_cast<std::size_t>(st.st_size) < sizeof(SegmentHeader)) {
      close(fd);
      throw ProtocolError("shared-memory segment " + name + " is truncated");
    }
    void* base = mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ, MAP_SHARED, fd, 0);
    if (base == MAP_FAILED) {
      close(fd);
      throw ProtocolError("shared-memory segment " + name + " cannot be mapped: " +
                          std::strerror(errno));
    }
    m = {name, base, static_cast<std::size_t>(st.st_size), fd, uses_};
    return m;
  }

  // Unmaps the segments of process `pid`: after its session no message points at them.
  void forget(pid_t pid) {
    std::lock_guard lock(mutex_);
    const std::string prefix = "/rockcut." + std::to_string(pid) + ".";
    for (auto it = by_slot_.begin(); it != by_slot_.end();) {
      if (it->first.starts_with(prefix)) {
        unmap(it->second);
        it = by_slot_.erase(it);
      } else {
        ++it;
      }
    }
  }

 private:
  // The least recently read mapping is not one of the message being read (a message has at most
  // Message::kMaxArrays arrays, a reader holds at most two messages' arrays at once).
  void evict_oldest() {
    auto oldest = by_slot_.begin();
    for (auto it = by_slot_.begin(); it != by_slot_.end(); ++it) {
      if (it->second.last_use < oldest->second.last_use) oldest = it;
    }
    unmap(oldest->second);
    by_slot_.erase(oldest);
  }

  std::mutex mutex_;
  std::unordered_map<std::string, Mapping> by_slot_;
  std::uint64_t uses_ = 0;
};

MappingCache& mappings() {
  static MappingCache cache;
  return cache;
}

}  // namespace

std::unique_ptr<SharedPayloadArena> SharedPayloadArena::for_endpoint(std::string_view endpoint) {
  if (!endpoint.starts_with("ipc://")) return nullptr;
  const char* env = std::getenv("ROCKCUT_WIRE_SHARED_MEMORY");
  if (env && std::string_view(env) == "0") return nullptr;
  return std::make_unique<SharedPayloadArena>();
}

// The clock's nanoseconds keep a name from meaning two segments when a pid is reused while a
// coupler still holds the older segment mapped.
SharedPayloadArena::SharedPayloadArena()
    : prefix_("/rockcut." + std::to_string(getpid()) + "." + std::to_string(arena_counter++) + "-" +
              std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + ".") {}

SharedPayloadArena::~SharedPayloadArena() {
  for (Slot& slot : slots_) {
    for (Segment& s : slot.turn) release(s);
  }
}

void SharedPayloadArena::release(Segment& segment) {
  if (!segment.base) return;
  munmap(segment.base, sizeof(SegmentHeader) + segment.capacity_bytes);
  shm_unlink(segment.name.c_str());
  segment.base = nullptr;
}

void SharedPayloadArena::create(const Slot& slot, unsigned turn, std::size_t bytes,
                                Segment& segment) {
  const std::uint64_t version = segment.version + 1;
  release(segment);
  // Room to grow by a quarter: a cut's wall-segment list or a frame's array may grow a little.
  const std::size_t capacity = bytes + bytes / 4;
  const std::size_t size = sizeof(SegmentHeader) + capacity;
  std::string name = prefix_ + slot.array_name + "." + std::to_string(turn) + ".v" +
                     std::to_string(version);
  const int fd = shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL, 0600);
  if (fd < 0) throw shm_error("shm_open", name);
  if (ftruncate(fd, static_cast<off_t>(size)) != 0) {
    const auto e = shm_error("ftruncate", name);
    close(fd);
    shm_unlink(name.c_str());
    throw e;
  }
  void* base = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  close(fd);
  if (base == MAP_FAILED) {
    const auto e = shm_error("mmap", name);
    shm_unlink(name.c_str());
    throw e;
  }
  auto* h = static_cast<SegmentHeader*>(base);
  h->magic = kMagic;
  segment = {std::move(name), base, capacity, version};
}

void SharedPayloadArena::write(std::span<const double> values, ArrayHeader& header) {
  Slot* slot = nullptr;
  for (Slot& s : slots_) {
    if (s.array_name == header.name()) slot = &s;
  }
  if (!slot) {
    slot = &slots_.emplace_back();
    slot->array_name = header.name();
  }
  const unsigned turn = slot->next;
  slot->next ^= 1u;
  Segment& segment = slot->turn[turn];
  if (!segment.base || segment.capacity_bytes < values.size_bytes()) {
    create(*slot, turn, values.size_bytes(), segment);
  }
  auto* h = static_cast<SegmentHeader*>(segment.base);
  std::memcpy(reinterpret_cast<char*>(segment.base) + sizeof(SegmentHeader), values.data(),
              values.size_bytes());
  h->bytes = values.size_bytes();
  __atomic_store_n(&h->generation, ++generation_, __ATOMIC_RELEASE);
  header.set_shared_segment(segment.name);
  header.set_shared_generation(generation_);
}

std::vector<std::string> SharedPayloadArena::segment_names() const {
  std::vector<std::string> names;
  for (const Slot& slot : slots_) {
    for (const Segment& s : slot.turn) {
      if (s.base) names.push_back(s.name);
    }
  }
  return names;
}

std::span<const double> read_shared(const ArrayHeader& header) {
  const Mapping& m = mappings().get(header.shared_segment(), header.name());
  // The size now, not at mapping time: a sender that shrank the segment since would make the
  // reads below fault (SIGBUS) past its new end.
  struct stat st {};
  const std::size_t size =
      fstat(m.fd, &st) == 0 ? std::min(m.size, static_cast<std::size_t>(st.st_size)) : 0;
  const auto* h = static_cast<const SegmentHeader*>(m.base);
  if (size < sizeof(SegmentHeader)) {
    throw ProtocolError("array '" + header.name() + "': shared-memory segment " + m.name +
                        " was truncated");
  }
  const std::uint64_t generation = __atomic_load_n(&h->generation, __ATOMIC_ACQUIRE);
  const std::size_t room = (size - sizeof(SegmentHeader)) / sizeof(double);
  // Compared by division: count * components may wrap for a count a peer made up.
  const std::uint64_t count = header.count();
  const std::uint32_t components = header.components();
  // The sender's own count of the bytes it wrote must match the header it sent.
  if (h->magic != kMagic || components == 0 || count > room / components ||
      h->bytes != count * components * sizeof(double)) {
    throw ProtocolError("array '" + header.name() + "': shared-memory segment " + m.name +
                        " does not hold " + std::to_string(count) + " x " +
                        std::to_string(components) + " doubles");
  }
  const std::size_t n = count * components;
  if (generation != header.shared_generation()) {
    throw ProtocolError("array '" + header.name() + "': shared-memory segment " + m.name +
                        " was written again (write " + std::to_string(generation) +
                        ") before write " + std::to_string(header.shared_generation()) +
                        " was read");
  }
  return {reinterpret_cast<const double*>(static_cast<const char*>(m.base) + sizeof(SegmentHeader)),
          n};
}

namespace {
// Calls `f(file name, pid)` for every "rockcut.<pid>.*" entry of /dev/shm.
template <typename F>
void for_each_segment(F&& f) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/dev/shm", ec)) {
    const std::string file = entry.path().filename().string();
    if (!file.starts_with("rockcut.")) continue;
    const std::size_t dot = file.find('.', 8);
    if (dot == std::string::npos) continue;
    char* end = nullptr;
    const long pid = std::strtol(file.c_str() + 8, &end, 10);
    if (end != file.c_str() + dot || pid <= 0) continue;
    f(file, static_cast<pid_t>(pid));
  }
}
}  // namespace

void remove_orphaned_shared_segments() {
  for_each_segment([](const std::string& file, pid_t pid) {
    if (kill(pid, 0) != 0 && errno == ESRCH) shm_unlink(("/" + file).c_str());
  });
}

void remove_shared_segments_of(pid_t pid) {
  mappings().forget(pid);
  for_each_segment([pid](const std::string& file, pid_t owner) {
    if (owner == pid) shm_unlink(("/" + file).c_str());
  });
}

}  // namespace rockcut::wire
