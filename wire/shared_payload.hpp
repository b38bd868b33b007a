// Large arrays in POSIX shared memory between processes on one host (ipc://).
//
// Why: over ipc:// every array frame crosses the kernel twice per hop (into the socket, out of it)
// and is moved by the ZeroMQ I/O threads of both sides, on the two cores the modules compute on.
// At paper scale that cost an exchange several ms over ipc (bench/README.md, bench_exchange). With the arrays in shared memory a message carries only its envelope: the sending
// module copies an array once into its segment (as it copied it into a frame before), the coupler
// forwards the header without touching the values, and the receiver reads them in place.
//
// Layout: a sending module owns one arena; each array name has two segments used in turn, so
// the values of one message stay valid while the next is written. The protocol is lockstep: a
// receiver has read a message's arrays before it replies, and its sender writes the same array
// again only after that reply. Each write bumps a generation stored in the segment and in the
// header, so a reader that would see overwritten values gets a ProtocolError instead.
//
// Segment names: "/rockcut.<pid>.<arena>-<clock>.<array>.<turn>.v<version>" (a new version when an array
// outgrows its segment). The arena unlinks its segments when it is destroyed; the coupler removes
// what a killed module left behind (remove_shared_segments_of), and before an ipc run what any
// dead process left (remove_orphaned_shared_segments).
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rockcut/wire.pb.h"

namespace rockcut::wire {

class SharedPayloadArena {
 public:
  /// Arrays smaller than this stay in their frames: below it a copy through the socket costs
  /// less than the page-table work of a shared segment (bench_exchange, "shared memory").
  static constexpr std::size_t kMinBytes = 64 * 1024;

  /// An arena for a module serving `endpoint`, or nullptr where arrays stay in frames: endpoints
  /// other than ipc://, or the environment's ROCKCUT_WIRE_SHARED_MEMORY=0 (for comparisons).
  static std::unique_ptr<SharedPayloadArena> for_endpoint(std::string_view endpoint);

  SharedPayloadArena();
  ~SharedPayloadArena();
  SharedPayloadArena(const SharedPayloadArena&) = delete;
  SharedPayloadArena& operator=(const SharedPayloadArena&) = delete;

  /// Copies `values` into the next segment of `header.name()` and sets the header's
  /// shared_segment and shared_generation. Throws std::system_error if shared memory fails.
  void write(std::span<const double> values, ArrayHeader& header);

  /// Names of the segments that exist now (for tests).
  std::vector<std::string> segment_names() const;

 private:
  struct Segment {
    std::string name;
    void* base = nullptr;
    std::size_t capacity_bytes = 0;  // of values, after the segment's header
    std::uint64_t version = 0;
  };
  struct Slot {
    std::string array_name;
    Segment turn[2];
    unsigned next = 0;
  };
  void create(const Slot& slot, unsigned turn, std::size_t bytes, Segment& segment);
  static void release(Segment& segment);

  std::string prefix_;  // "/rockcut.<pid>.<arena>-<clock>."
  std::vector<Slot> slots_;
  std::uint64_t generation_ = 0;
};

/// The values `header` points to in shared memory, mapped read-only on first use and kept mapped.
/// Throws ProtocolError if the segment is missing, too small or was written again since.
std::span<const double> read_shared(const ArrayHeader& header);

/// Unlinks the segments of the process `pid` (a module that was killed cannot unlink its own)
/// and unmaps this process's views of them; called when the session with `pid` has ended.
void remove_shared_segments_of(pid_t pid);

/// Unlinks the segments of processes that no longer exist: what modules killed together with
/// their coupler (SIGKILL, PR_SET_PDEATHSIG) left behind. The coupler calls it before an ipc run.
void remove_orphaned_shared_segments();

}  // namespace rockcut::wire
