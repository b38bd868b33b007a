// Waiting for a reply by polling before sleeping. A blocking ZeroMQ receive sleeps in the kernel,
// and on this machine waking the sleeping thread costs tens of microseconds per message (an
// inter-processor interrupt through the hypervisor). A small coupled scene exchanges every few
// hundred microseconds, four messages per exchange, so those wake-ups are a large part of its
// wall time. Polling first, yielding the core between polls, catches a reply that comes soon.
//
// On by default on two or more cores (kDefaultSpinUs); ROCKCUT_WIRE_SPIN_US (microseconds, 0 =
// sleep at once) overrides it, like GOMP_SPINCOUNT for OpenMP. The poll stops early when the core
// is wanted: a poll that comes back more than kContendedPollUs after the last one means the yield
// gave the core to a thread with work, e.g. of another run sharing the cores. Polling shortens
// the default scene by a sixth and lengthens runs that share the cores (docs/performance.md,
// "Polling"), so the tools that run jobs side by side set 0.
#pragma once

#include <chrono>

#include <zmq.hpp>

namespace rockcut::wire {

/// The polling budget when ROCKCUT_WIRE_SPIN_US is not set [us].
inline constexpr long kDefaultSpinUs = 200;
/// A gap between two polls longer than this [us] means another thread had the core.
inline constexpr long kContendedPollUs = 50;

/// The budget for ROCKCUT_WIRE_SPIN_US = `value` (nullptr: unset) on a machine with `cores`
/// cores [us]: a non-negative integer is taken as given; unset or anything else gives
/// kDefaultSpinUs on two or more cores and 0 on one, where a polling thread only delays the
/// thread it waits for.
long parse_spin_budget_us(const char* value, unsigned cores);

/// The polling budget of this process [us], read once from ROCKCUT_WIRE_SPIN_US.
long spin_budget_us();

/// Polls `socket` for input for up to spin_budget_us(), yielding the core between polls. Returns
/// when a message is waiting, the budget is spent, or the core is wanted by another thread; the
/// caller then receives or blocks as before. Returns true in the last case (for tests).
bool spin_until_readable(zmq::socket_t& socket);
/// The same with an explicit budget [us] (0: return at once).
bool spin_until_readable(zmq::socket_t& socket, long budget_us);

/// The polling loop itself, with its clock, poll and yield given: `now()` returns a
/// steady_clock::time_point, `ready()` is true when the wait should end (a message waits, or the
/// poll failed and the caller's blocking wait should handle it), `yield()` offers the core.
/// Returns true when a gap between two polls exceeded kContendedPollUs. Tests drive it with a
/// scripted clock, so the rule is checked without depending on the machine's load.
template <class Now, class Ready, class Yield>
bool spin_until(long budget_us, Now&& now, Ready&& ready, Yield&& yield) {
  if (budget_us <= 0) return false;
  const auto start = now();
  const auto end = start + std::chrono::microseconds(budget_us);
  auto before = start;
  while (true) {
    if (ready()) return false;
    yield();  // a thread that has work on this core gets it
    const auto after = now();
    // The yield handed the core to a thread with work (another run, or this run's own module),
    // or the thread was preempted: the core is wanted, so stop polling and sleep.
    if (after - before > std::chrono::microseconds(kContendedPollUs)) return true;
    if (after >= end) return false;
    before = after;
  }
}

}  // namespace rockcut::wire
