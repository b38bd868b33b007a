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
  // A poll that finds the core taken ends early (true). The hypervisor of this machine takes the
  // core for more than kContendedPollUs every few milliseconds, so a 20 ms poll may end that way;
  // one that does not must have run its whole budget.
  int whole_budgets = 0;
  for (int k = 0; k < 5; ++k) {
    const auto start = clock_type::now();
    const bool contended = spin_until_readable(b, 20'000);  // 20 ms
    const double waited = seconds_since(start);
    EXPECT_LT(waited, 0.5);  // the budget plus scheduling delays on a loaded machine
    if (!contended) {
      EXPECT_GE(waited, 0.020);
      ++whole_budgets;
    }
  }
  RecordProperty("whole_budgets_of_5", whole_budgets);
  auto start = clock_type::now();
  start = clock_type::now();
  spin_until_readable(b, 0);  // off: returns without polling
  EXPECT_LT(seconds_since(start), 0.010);
}

TEST(SpinWait, BudgetIsTheVariableOrTheDefaultOnTwoOrMoreCores) {
  EXPECT_EQ(parse_spin_budget_us(nullptr, 2), kDefaultSpinUs);
  EXPECT_EQ(parse_spin_budget_us(nullptr, 64), kDefaultSpinUs);
  EXPECT_EQ(parse_spin_budget_us(nullptr, 1), 0);  // one core: polling only delays the sender
  EXPECT_EQ(parse_spin_budget_us("0", 2), 0);      // off
  EXPECT_EQ(parse_spin_budget_us("1000", 1), 1000);
  EXPECT_EQ(parse_spin_budget_us("", 2), kDefaultSpinUs);
  EXPECT_EQ(parse_spin_budget_us("20x", 2), kDefaultSpinUs);
  EXPECT_EQ(parse_spin_budget_us("-5", 2), kDefaultSpinUs);
}

TEST(SpinWait, ReportsNoContentionWhenTheCoreIsFree) {
  // Nothing else wants this core in the test (ctest runs at most two tests on two cores): the
  // gaps between polls stay far below kContendedPollUs, so the poll runs its whole budget.
  // A loaded machine can preempt the thread anyway (the integration tests beside this one run
  // three processes each), so one clean 200 us poll out of up to 100 suffices; a poll that
  // misreads free gaps as contention fails all of them.
  zmq::context_t context;
  zmq::socket_t b(context, zmq::socket_type::pair);
  b.bind("inproc://free");
  bool clean = false;
  for (int k = 0; k < 100 && !clean; ++k) clean = !spin_until_readable(b, 200);
  EXPECT_TRUE(clean);
}

}  // namespace
}  // namespace rockcut::wire
