// Polling before sleeping (ROCKCUT_WIRE_SPIN_US): it must return at once when a message waits,
// give up after its budget when none comes, and never take the message itself.
#include <gtest/gtest.h>

#include <chrono>

#include <zmq.hpp>

#include "wire/spin_wait.hpp"

namespace rockcut::wire {
namespace {

using clock_type = std::chrono::steady_clock;

double seconds_since(clock_type::time_point t) {
  return std::chrono::duration<double>(clock_type::now() - t).count();
}

TEST(SpinWait, ReturnsAtOnceWhenAMessageWaitsAndLeavesItThere) {
  zmq::context_t context;
  zmq::socket_t a(context, zmq::socket_type::pair), b(context, zmq::socket_type::pair);
  a.bind("inproc://spin");
  b.connect("inproc://spin");
  a.send(zmq::str_buffer("x"), zmq::send_flags::none);
  const auto start = clock_type::now();
  spin_until_readable(b, 2'000'000);  // 2 s budget
  // Well under the budget: one poll and out. 0.5 s leaves room for a descheduled test thread.
  EXPECT_LT(seconds_since(start), 0.5);
  zmq::message_t m;
  ASSERT_TRUE(b.recv(m, zmq::recv_flags::dontwait));  // still there for the caller
  EXPECT_EQ(m.to_string(), "x");
}

TEST(SpinWait, GivesUpAfterItsBudget) {
  zmq::context_t context;
  zmq::socket_t b(context, zmq::socket_type::pair);
  b.bind("inproc://silent");
  auto start = clock_type::now();
  spin_until_readable(b, 20'000);  // 20 ms
  const double waited = seconds_since(start);
  EXPECT_GE(waited, 0.020);
  EXPECT_LT(waited, 0.5);  // the budget plus scheduling delays on a loaded machine
  start = clock_type::now();
  spin_until_readable(b, 0);  // off: returns without polling
  EXPECT_LT(seconds_since(start), 0.010);
}

}  // namespace
}  // namespace rockcut::wire
