#include "wire/connection_watch.hpp"

#include <atomic>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace rockcut::wire {

namespace {
std::string next_monitor_address() {
  static std::atomic<unsigned> counter{0};
  return "inproc://rockcut.monitor." + std::to_string(counter.fetch_add(1));
}
}  // namespace

ConnectionWatch::ConnectionWatch(zmq::context_t& context, zmq::socket_t& socket)
    : watched_(socket), monitor_(context, zmq::socket_type::pair) {
  const std::string address = next_monitor_address();
  if (zmq_socket_monitor(socket.handle(), address.c_str(), ZMQ_EVENT_DISCONNECTED) != 0) {
    throw std::runtime_error(std::string("cannot monitor a socket: ") + zmq_strerror(zmq_errno()));
  }
  monitor_.set(zmq::sockopt::linger, 0);
  monitor_.connect(address);
}

ConnectionWatch::~ConnectionWatch() {
  zmq_socket_monitor(watched_.handle(), nullptr, 0);  // stops the monitor before its peer goes
}

int ConnectionWatch::take_disconnection() {
  int fd = -1;
  for (;;) {
    zmq::message_t event;
    zmq::recv_result_t got;
    try {
      got = monitor_.recv(event, zmq::recv_flags::dontwait);
    } catch (const zmq::error_t&) {
      return fd;
    }
    if (!got) return fd;
    // Frame 1: the event (uint16) and its value (uint32, the fd); frame 2: the endpoint.
    std::uint16_t id = 0;
    std::uint32_t value = 0;
    if (event.size() >= 6) {
      std::memcpy(&id, event.data(), 2);
      std::memcpy(&value, static_cast<const char*>(event.data()) + 2, 4);
    }
    while (event.more()) {
      zmq::message_t rest;
      if (!monitor_.recv(rest, zmq::recv_flags::dontwait)) break;
      if (!rest.more()) break;
    }
    if (id == ZMQ_EVENT_DISCONNECTED) fd = static_cast<int>(value);
  }
}

int source_fd(const zmq::message_t& message) {
  // zmq_msg_get takes a non-const message; it only reads the property.
  return zmq_msg_get(const_cast<zmq_msg_t*>(message.handle()), ZMQ_SRCFD);
}

}  // namespace rockcut::wire
