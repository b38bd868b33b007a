// Waiting for a reply by polling before sleeping. A blocking ZeroMQ receive sleeps in the kernel,
// and on this machine waking the sleeping thread costs tens of microseconds per message (an
// inter-processor interrupt through the hypervisor). A small coupled scene exchanges every few
// hundred microseconds, four messages per exchange, so those wake-ups are a large part of its
// wall time. Polling first, yielding the core between polls, catches a reply that comes soon.
//
// Opt-in, like GOMP_SPINCOUNT: ROCKCUT_WIRE_SPIN_US (microseconds, default 0 = sleep at once).
// Measured (bench/README.md, bench_coupled.py): with 200 us the reduced saturated cut takes a third
// less wall time inproc and a sixth less over ipc; at paper scale, where both modules run two
// OpenMP threads on the two cores, it made no difference beyond the noise. Runs that share the
// cores with other runs (scripts/sweep --jobs 2) should leave it off.
#pragma once

#include <zmq.hpp>

namespace rockcut::wire {

/// The polling budget from ROCKCUT_WIRE_SPIN_US [us], read once; 0 if unset or not a number.
long spin_budget_us();

/// Polls `socket` for input for up to spin_budget_us(), yielding the core between polls. Returns
/// when a message is waiting or the budget is spent; the caller then receives or blocks as before.
void spin_until_readable(zmq::socket_t& socket);
/// The same with an explicit budget [us] (0: return at once).
void spin_until_readable(zmq::socket_t& socket, long budget_us);

}  // namespace rockcut::wire
