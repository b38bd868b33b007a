// A connected socket pair inside one context, what the coupler and a module see, for the wire
// tests.
#pragma once

#include <string>
#include <zmq.hpp>

namespace rockcut::wire::test_support {

struct SocketPair {
  zmq::context_t context{1};
  zmq::socket_t a{context, zmq::socket_type::pair};
  zmq::socket_t b{context, zmq::socket_type::pair};
  explicit SocketPair(const std::string& name = "pair") {
    a.bind("inproc://" + name);
    b.connect("inproc://" + name);
  }
};

}  // namespace rockcut::wire::test_support
