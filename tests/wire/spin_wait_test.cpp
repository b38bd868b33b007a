// Polling before sleeping (ROCKCUT_WIRE_SPIN_US): it must return at once when a message waits,
// give up after its budget when none comes, stop when the core is wanted, and never take the
// message itself. The stopping rule is checked on the loop with a scripted clock, so it does not
// depend on what else the machine runs; the real socket checks only bound what a busy machine
// cannot break.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <vector>

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

// The loop under a scripted clock: each now() returns the next of `gaps_us` added up, so a test
// says exactly how long each poll-and-yield took.
struct ScriptedLoop {
  std::vector<long> gaps_us;  // the time each poll-and-yield takes [us]; the last one repeats
  int ready_at_poll = -1;     // the poll that finds a message (-1: none comes)
  int polls = 0, yields = 0, clock_reads = 0;
  clock_type::time_point t{};

  bool run(long budget_us) {
    return spin_until(
        budget_us,
        [this] {
          if (clock_reads > 0) {
            const std::size_t k = std::min<std::size_t>(clock_reads - 1, gaps_us.size() - 1);
            t += std::chrono::microseconds(gaps_us[k]);
          }
          ++clock_reads;
          return t;
        },
        [this] { return polls++ == ready_at_poll; }, [this] { ++yields; });
  }
};

TEST(SpinWait, AFreeCoreRunsTheWholeBudget) {
  // 10 us per poll and yield, well below kContendedPollUs: the 200 us budget is spent in 20 polls.
  ScriptedLoop loop{{10}};
  EXPECT_FALSE(loop.run(200));
  EXPECT_EQ(loop.polls, 20);
  EXPECT_EQ(loop.yields, 20);
  // A gap of exactly kContendedPollUs is still a free core.
  ScriptedLoop edge{{kContendedPollUs}};
  EXPECT_FALSE(edge.run(4 * kContendedPollUs));
  EXPECT_EQ(edge.polls, 4);
}

TEST(SpinWait, AGapLongerThanTheThresholdMeansTheCoreIsWanted) {
  // The fourth yield gives the core away for kContendedPollUs + 1 us: the loop stops there, long
  // before its budget.
  ScriptedLoop loop{{10, 10, 10, kContendedPollUs + 1, 10}};
  EXPECT_TRUE(loop.run(10'000));
  EXPECT_EQ(loop.polls, 4);
}

TEST(SpinWait, AWaitingMessageEndsTheLoopAtThatPoll) {
  ScriptedLoop loop{{10}};
  loop.ready_at_poll = 2;  // the third poll finds it
  EXPECT_FALSE(loop.run(200));
  EXPECT_EQ(loop.polls, 3);
  EXPECT_EQ(loop.yields, 2);  // no yield after the message is found
}

TEST(SpinWait, AZeroBudgetNeitherPollsNorReadsTheClock) {
  ScriptedLoop loop{{10}};
  EXPECT_FALSE(loop.run(0));
  EXPECT_FALSE(loop.run(-5));
  EXPECT_EQ(loop.polls + loop.yields + loop.clock_reads, 0);
}

}  // namespace
}  // namespace rockcut::wire
