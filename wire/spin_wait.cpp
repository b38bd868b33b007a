#include "wire/spin_wait.hpp"

#include <sched.h>

#include <chrono>
#include <cstdlib>
#include <thread>

namespace rockcut::wire {

long parse_spin_budget_us(const char* value, unsigned cores) {
  if (value) {
    char* end = nullptr;
    const long us = std::strtol(value, &end, 10);
    if (end != value && *end == '\0' && us >= 0) return us;
  }
  return cores >= 2 ? kDefaultSpinUs : 0L;
}

long spin_budget_us() {
  static const long budget = parse_spin_budget_us(std::getenv("ROCKCUT_WIRE_SPIN_US"),
                                                  std::thread::hardware_concurrency());
  return budget;
}

bool spin_until_readable(zmq::socket_t& socket) {
  return spin_until_readable(socket, spin_budget_us());
}

bool spin_until_readable(zmq::socket_t& socket, long budget) {
  return spin_until(
      budget, [] { return std::chrono::steady_clock::now(); },
      [&socket] {
        zmq::pollitem_t item{socket.handle(), 0, ZMQ_POLLIN, 0};
        try {
          zmq::poll(&item, 1, std::chrono::milliseconds(0));
        } catch (const zmq::error_t&) {
          return true;  // EINTR and the rest: the caller's blocking wait handles them
        }
        return (item.revents & ZMQ_POLLIN) != 0;
      },
      [] { sched_yield(); });
}

}  // namespace rockcut::wire
