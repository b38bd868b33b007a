#include "wire/spin_wait.hpp"

#include <sched.h>

#include <chrono>
#include <cstdlib>

namespace rockcut::wire {

long spin_budget_us() {
  static const long budget = [] {
    const char* value = std::getenv("ROCKCUT_WIRE_SPIN_US");
    if (!value) return 0L;
    char* end = nullptr;
    const long us = std::strtol(value, &end, 10);
    return end != value && *end == '\0' && us > 0 ? us : 0L;
  }();
  return budget;
}

void spin_until_readable(zmq::socket_t& socket) { spin_until_readable(socket, spin_budget_us()); }

void spin_until_readable(zmq::socket_t& socket, long budget) {
  if (budget <= 0) return;
  using clock = std::chrono::steady_clock;
  const auto end = clock::now() + std::chrono::microseconds(budget);
  do {
    zmq::pollitem_t item{socket.handle(), 0, ZMQ_POLLIN, 0};
    try {
      zmq::poll(&item, 1, std::chrono::milliseconds(0));
    } catch (const zmq::error_t&) {
      return;  // EINTR and the rest: the caller's blocking wait handles them
    }
    if (item.revents & ZMQ_POLLIN) return;
    sched_yield();  // a module thread that has work gets the core
  } while (clock::now() < end);
}

}  // namespace rockcut::wire
