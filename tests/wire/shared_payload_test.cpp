// Arrays in shared memory over ipc:// (wire/shared_payload.hpp): the same bits as frames, headers
// forwarded without copies, overwritten values refused, segments that outgrow or outlive their
// writer removed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <numeric>

#include "wire/message.hpp"
#include "wire/shared_payload.hpp"
#include "wire/socket_pair.hpp"

namespace rockcut::wire {
namespace {

namespace fs = std::filesystem;

using test_support::SocketPair;

bool segment_exists(const std::string& name) { return fs::exists("/dev/shm" + name); }

std::vector<double> ramp(std::size_t n, double start) {
  std::vector<double> v(n);
  std::iota(v.begin(), v.end(), start);
  return v;
}

const ArrayHeader& header_of(const Message& m, const std::string& name) {
  for (const ArrayHeader& h : m.envelope.arrays()) {
    if (h.name() == name) return h;
  }
  throw std::runtime_error("no header " + name);
}

TEST(SharedPayload, LargeArraysTravelInSharedMemorySmallOnesInFrames) {
  SocketPair p("shm_large_small");
  SharedPayloadArena arena;
  // 10,000 particles' positions (160 kB) and 100 radii (800 bytes): one on each side of kMinBytes.
  const std::vector<double> position = ramp(20000, 0.25), radius = ramp(100, -1.5);
  Message out;
  out.use_arena(&arena);
  out.envelope.mutable_kinematics();
  out.add_array("position", position, 2);
  out.add_array("radius", radius, 1);
  out.send(p.a);

  // What crossed the socket: the envelope, an empty frame and the radii's 800 bytes.
  std::vector<zmq::message_t> parts;
  for (bool more = true; more;) {
    zmq::message_t part;
    ASSERT_TRUE(p.b.recv(part));
    more = part.more();
    parts.push_back(std::move(part));
  }
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts[1].size(), 0u);
  EXPECT_EQ(parts[2].size(), radius.size() * sizeof(double));

  // The same message through Message::receive gives both arrays bit for bit.
  out.clear();
  out.envelope.mutable_kinematics();
  out.add_array("position", position, 2);
  out.add_array("radius", radius, 1);
  out.send(p.a);
  Message in;
  in.receive(p.b);
  EXPECT_FALSE(header_of(in, "position").shared_segment().empty());
  EXPECT_TRUE(header_of(in, "radius").shared_segment().empty());
  const auto x = in.array("position", 2);
  const auto r = in.array("radius", 1);
  ASSERT_EQ(x.size(), position.size());
  EXPECT_EQ(std::memcmp(x.data(), position.data(), x.size_bytes()), 0);
  EXPECT_EQ(std::vector<double>(r.begin(), r.end()), radius);
  EXPECT_EQ(in.payload_bytes(), (20000 + 100) * sizeof(double));
  EXPECT_EQ(in.shared_payload_bytes(), 20000 * sizeof(double));
}

TEST(SharedPayload, ForwardedHeadersPointAtTheSenderSegmentWithoutACopy) {
  // The coupler forwards the DEM's positions to the fluid: the fluid reads the DEM's segment.
  SocketPair dem_to_coupler("shm_fwd_1"), coupler_to_fluid("shm_fwd_2");
  SharedPayloadArena arena;
  const std::vector<double> position = ramp(30000, 3.0);
  Message from_dem;
  from_dem.use_arena(&arena);
  from_dem.envelope.mutable_kinematics();
  from_dem.add_array("position", position, 2);
  from_dem.send(dem_to_coupler.a);

  Message at_coupler, forwarded, at_fluid;
  at_coupler.receive(dem_to_coupler.b);
  const double* coupler_view = at_coupler.array("position", 2).data();
  forwarded.envelope.mutable_fluid_step();
  forwarded.take_arrays(at_coupler);
  forwarded.send(coupler_to_fluid.a);
  at_fluid.receive(coupler_to_fluid.b);
  const auto x = at_fluid.array("position", 2);
  EXPECT_EQ(x.data(), coupler_view) << "one mapping of the segment per process, no copy";
  EXPECT_EQ(std::memcmp(x.data(), position.data(), x.size_bytes()), 0);

  // The session with the sender is over (the coupler's ModuleLink::close): its segments are
  // unlinked and this process's mapping of them dropped, so the array can no longer be read.
  remove_shared_segments_of(getpid());
  EXPECT_THROW(at_fluid.array("position", 2), ProtocolError);
}

TEST(SharedPayload, ValuesWrittenAgainBeforeTheyAreReadAreRefused) {
  SocketPair p("shm_overwrite");
  SharedPayloadArena arena;
  std::vector<Message> sent(3);
  for (int k = 0; k < 3; ++k) {
    sent[k].use_arena(&arena);
    sent[k].envelope.mutable_fluid_result();
    sent[k].add_array("force", ramp(20000, 10.0 * k), 2);
    sent[k].send(p.a);
  }
  std::vector<Message> got(3);
  for (Message& m : got) m.receive(p.b);
  // Two segments in turn: the third write reused the first message's segment.
  try {
    got[0].array("force", 2);
    ADD_FAILURE() << "an overwritten array was read";
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("was written again"), std::string::npos) << e.what();
  }
  EXPECT_EQ(got[1].array("force", 2)[0], 10.0);
  EXPECT_EQ(got[2].array("force", 2)[0], 20.0);
}

TEST(SharedPayload, AnArrayThatOutgrowsItsSegmentMovesToANewOne) {
  SocketPair p("shm_grow");
  SharedPayloadArena arena;
  Message m;
  m.use_arena(&arena);
  std::vector<std::string> first_names;
  for (std::size_t n : {10000, 10000, 40000}) {  // the third write needs turn 0 four times larger
    m.clear();
    m.envelope.mutable_frame();
    m.add_array("position", ramp(n, 1.0), 2);
    first_names.push_back(header_of(m, "position").shared_segment());
    m.send(p.a);
    Message in;
    in.receive(p.b);
    const auto x = in.array("position", 2);
    ASSERT_EQ(x.size(), n);
    EXPECT_EQ(x[n - 1], static_cast<double>(n));
  }
  EXPECT_NE(first_names[0], first_names[2]);
  EXPECT_FALSE(segment_exists(first_names[0])) << "the outgrown segment is unlinked";
  EXPECT_TRUE(segment_exists(first_names[2]));
  EXPECT_EQ(arena.segment_names().size(), 2u);
}

TEST(SharedPayload, SegmentsAreUnlinkedByTheirArenaOrForAKilledProcess) {
  std::vector<std::string> names;
  {
    SharedPayloadArena arena;
    Message m;
    m.use_arena(&arena);
    m.add_array("force", ramp(20000, 0.0), 2);
    names = arena.segment_names();
    ASSERT_EQ(names.size(), 1u);
    EXPECT_TRUE(segment_exists(names[0]));
  }
  EXPECT_FALSE(segment_exists(names[0]));

  // What the coupler does for a module that was killed: every segment of that pid goes.
  SharedPayloadArena arena;
  Message m;
  m.use_arena(&arena);
  m.add_array("force", ramp(20000, 0.0), 2);
  m.add_array("position", ramp(20000, 0.0), 2);
  names = arena.segment_names();
  ASSERT_EQ(names.size(), 2u);
  remove_shared_segments_of(getpid());
  for (const std::string& n : names) EXPECT_FALSE(segment_exists(n)) << n;
}

TEST(SharedPayload, OnlyIpcEndpointsGetAnArenaUnlessSwitchedOff) {
  EXPECT_NE(SharedPayloadArena::for_endpoint("ipc:///tmp/x.sock"), nullptr);
  EXPECT_EQ(SharedPayloadArena::for_endpoint("inproc://dem"), nullptr);
  EXPECT_EQ(SharedPayloadArena::for_endpoint("tcp://127.0.0.1:5555"), nullptr);
  setenv("ROCKCUT_WIRE_SHARED_MEMORY", "0", 1);
  EXPECT_EQ(SharedPayloadArena::for_endpoint("ipc:///tmp/x.sock"), nullptr);
  unsetenv("ROCKCUT_WIRE_SHARED_MEMORY");
}

}  // namespace
}  // namespace rockcut::wire
