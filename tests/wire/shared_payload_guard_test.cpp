// A reader of shared-memory arrays against a careless or hostile sender: a segment shrunk after
// it was mapped, names outside the arenas' scheme, counts that wrap, and ever new names.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "wire/message.hpp"
#include "wire/shared_payload.hpp"

namespace rockcut::wire {
namespace {

std::size_t mapped_rockcut_segments() {
  std::ifstream maps("/proc/self/maps");
  std::size_t n = 0;
  for (std::string line; std::getline(maps, line);) n += line.find("/dev/shm/rockcut.") != std::string::npos;
  return n;
}

TEST(SharedPayloadGuard, ASegmentShrunkAfterMappingIsRefusedNotASigbus) {
  SharedPayloadArena arena;
  const std::vector<double> values(100000, 1.5);
  ArrayHeader header;
  header.set_name("position");
  header.set_count(values.size() / 2);
  header.set_components(2);
  arena.write(values, header);
  ASSERT_EQ(read_shared(header)[99999], 1.5);  // mapped now
  const int fd = shm_open(header.shared_segment().c_str(), O_RDWR, 0);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(ftruncate(fd, 4096), 0);  // the sender shrinks it under the reader
  close(fd);
  EXPECT_THROW(read_shared(header), ProtocolError);
}

TEST(SharedPayloadGuard, NamesOutsideTheSchemeAndWrappingCountsAreRefused) {
  SharedPayloadArena arena;
  const std::vector<double> values(16, 2.0);
  ArrayHeader header;
  header.set_name("force");
  header.set_count(8);
  header.set_components(2);
  arena.write(values, header);
  ASSERT_EQ(read_shared(header).size(), 16u);
  for (const std::string name : {"/etc/passwd", "/rockcut.x.force.0.v1", "rockcut.1.0-1.force.0.v1",
                                 "/rockcut.1.0-1.position.0.v1", "/rockcut.1.0-1.force.2.v1",
                                 "/rockcut.1.0-1/../../etc.force.0.v1", "/other.1.0-1.force.0.v1"}) {
    ArrayHeader bad = header;
    bad.set_shared_segment(name);
    EXPECT_THROW(read_shared(bad), ProtocolError) << name;
  }
  ArrayHeader wrap = header;
  wrap.set_count((std::uint64_t{1} << 62) + 8);  // * 2 * 8 bytes wraps to 256
  EXPECT_THROW(read_shared(wrap), ProtocolError);
  wrap.set_count(8);
  wrap.set_components(0);
  EXPECT_THROW(read_shared(wrap), ProtocolError);
}

TEST(SharedPayloadGuard, EverNewSegmentNamesKeepABoundedNumberOfMappings) {
  const std::size_t before = mapped_rockcut_segments();
  const std::vector<double> values(4, 3.0);
  for (int k = 0; k < 2000; ++k) {
    SharedPayloadArena arena;  // a new name each time; unlinked and unmapped by its writer at once
    ArrayHeader header;
    header.set_name("force");
    header.set_count(2);
    header.set_components(2);
    arena.write(values, header);
    ASSERT_EQ(read_shared(header)[3], 3.0);
  }
  EXPECT_LE(mapped_rockcut_segments(), before + 4 * Message::kMaxArrays);
}

}  // namespace
}  // namespace rockcut::wire
