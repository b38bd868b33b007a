// The wire layer: raw array frames, forwarding without copies, malformed messages.
#include <gtest/gtest.h>

#include <numeric>

#include "wire/message.hpp"
#include "wire/socket_pair.hpp"

namespace rockcut::wire {
namespace {

using test_support::SocketPair;

TEST(Message, ArraysRoundTripBitForBit) {
  SocketPair p;
  std::vector<double> position(2000), radius(1000);
  std::iota(position.begin(), position.end(), 0.125);
  std::iota(radius.begin(), radius.end(), -3.5);
  Message out;
  out.envelope.mutable_kinematics()->set_time_s(1.5);
  out.add_array("position", position, 2);
  out.add_array("radius", radius, 1);
  out.send(p.a);

  Message in;
  in.receive(p.b);
  ASSERT_TRUE(in.envelope.has_kinematics());
  EXPECT_EQ(in.envelope.kinematics().time_s(), 1.5);
  const auto pos = in.array("position", 2);
  const auto rad = in.array("radius", 1);
  ASSERT_EQ(pos.size(), position.size());
  ASSERT_EQ(rad.size(), radius.size());
  EXPECT_TRUE(std::equal(pos.begin(), pos.end(), position.begin()));
  EXPECT_TRUE(std::equal(rad.begin(), rad.end(), radius.begin()));
  EXPECT_EQ(in.payload_bytes(), (2000 + 1000) * sizeof(double));
}

TEST(Message, SmallArraysAreReadEvenWhenZeroMqStoresThemUnaligned) {
  // ZeroMQ keeps messages under 33 bytes inside the message object, possibly unaligned.
  SocketPair p;
  const std::vector<double> tiny = {1.0, -2.0, 3.0};
  for (int k = 0; k < 4; ++k) {
    Message out;
    out.envelope.mutable_frame();
    out.add_array("radius", tiny, 1);
    out.send(p.a);
    Message in;
    in.receive(p.b);
    const auto values = in.array("radius", 1);
    EXPECT_EQ(std::vector<double>(values.begin(), values.end()), tiny);
  }
}

TEST(Message, TakeArraysForwardsWithoutTouchingTheData) {
  SocketPair p;
  std::vector<double> force(10, 4.0);
  Message reply;
  reply.envelope.mutable_fluid_result();
  reply.add_array("force", force, 2);
  reply.send(p.a);
  Message received;
  received.receive(p.b);
  const double* data = received.array("force", 2).data();

  Message forward;
  forward.envelope.mutable_apply_forces();
  forward.take_arrays(received);
  EXPECT_FALSE(received.has_array("force"));
  ASSERT_TRUE(forward.has_array("force"));
  EXPECT_EQ(forward.array("force", 2).data(), data) << "the frame was copied, not moved";
}

TEST(Message, MismatchesAreProtocolErrors) {
  Message m;
  std::vector<double> v(6, 1.0);
  m.add_array("position", v, 2);
  EXPECT_THROW(m.array("position", 1), ProtocolError);
  EXPECT_THROW(m.array("velocity", 2), ProtocolError);
  std::vector<double> odd(5, 1.0);
  EXPECT_THROW(m.add_array("position", odd, 2), ProtocolError);
}

TEST(Message, GarbageFrameIsRejected) {
  SocketPair p;
  const std::string junk = "\xff\xff\xff not a protobuf";
  p.a.send(zmq::buffer(junk));
  Message in;
  EXPECT_THROW(in.receive(p.b), ProtocolError);
}

TEST(Message, MissingFramesAreRejected) {
  SocketPair p;
  Envelope e;
  ArrayHeader* h = e.add_arrays();
  h->set_name("force");
  h->set_count(3);
  h->set_components(2);
  const std::string bytes = e.SerializeAsString();
  p.a.send(zmq::buffer(bytes));  // announces one array, sends none
  Message in;
  EXPECT_THROW(in.receive(p.b), ProtocolError);
}

}  // namespace
}  // namespace rockcut::wire
