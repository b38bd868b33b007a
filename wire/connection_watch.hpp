// Watching a tcp socket's connections through ZeroMQ's socket monitor (zmq_socket_monitor): the
// coupler learns that its module's connection dropped (a TCP reset, the host gone) at once instead
// of waiting out the coupling timeout and blaming a module that is alive, and a module ends a
// session whose coupler's connection dropped instead of staying up, owned by a dead session, and
// refusing every other coupler.
#pragma once

#include <string>

#include <zmq.hpp>

namespace rockcut::wire {

class ConnectionWatch {
 public:
  /// Monitors `socket`'s disconnections (over an inproc PAIR socket of `context`).
  ConnectionWatch(zmq::context_t& context, zmq::socket_t& socket);
  ~ConnectionWatch();
  ConnectionWatch(const ConnectionWatch&) = delete;
  ConnectionWatch& operator=(const ConnectionWatch&) = delete;

  /// The socket to poll for events (ZMQ_POLLIN).
  zmq::socket_t& events() { return monitor_; }
  /// Reads the events that wait; returns the file descriptor of the last disconnection among
  /// them, -1 if none.
  int take_disconnection();

 private:
  zmq::socket_t& watched_;
  zmq::socket_t monitor_;
};

/// The file descriptor of the connection a received message came in on (ZeroMQ's ZMQ_SRCFD);
/// -1 where the transport has none.
int source_fd(const zmq::message_t& message);

}  // namespace rockcut::wire
