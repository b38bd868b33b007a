#include "wire/module_client.hpp"

#include <algorithm>

#include "wire/module_server.hpp"
#include "wire/spin_wait.hpp"

namespace rockcut::wire {

namespace {
// How often a waiting coupler looks at process liveness and signals.
constexpr std::chrono::milliseconds kPollSlice{50};
}  // namespace

ModuleClient::ModuleClient(zmq::context_t& context, std::string module_name,
                           const std::string& endpoint, std::chrono::milliseconds timeout,
                           ClientHooks hooks, const std::optional<CurveClientKeys>& curve)
    : name_(std::move(module_name)),
      socket_(context, zmq::socket_type::req),
      timeout_(timeout),
      hooks_(std::move(hooks)),
      endpoint_(endpoint) {
  socket_.set(zmq::sockopt::linger, 0);
  // A reply frame is bounded like a request's (module_server.hpp): a module announcing more is
  // disconnected before anything is buffered, and then named when the timeout passes.
  socket_.set(zmq::sockopt::maxmsgsize, kMaxMessageBytesBeforeInit);
  if (curve) {
    curve_ = true;
    socket_.set(zmq::sockopt::curve_serverkey, curve->server_key);
    socket_.set(zmq::sockopt::curve_publickey, curve->public_key);
    socket_.set(zmq::sockopt::curve_secretkey, curve->secret_key);
  }
  if (endpoint.starts_with("tcp://")) watch_ = std::make_unique<ConnectionWatch>(context, socket_);
  socket_.connect(endpoint);
}

void ModuleClient::send(Message& request) {
  try {
    request.send(socket_);
  } catch (const zmq::error_t& e) {
    throw ModuleFailure(name_, std::string("cannot send: ") + e.what());
  }
}

void ModuleClient::receive(Message& reply, bool interruptible) {
  using clock = std::chrono::steady_clock;
  auto deadline = clock::now() + timeout_;
  // Checked before waiting too: fast replies would otherwise never leave time to notice a signal.
  if (interruptible && hooks_.interrupted && hooks_.interrupted()) throw Interrupted();
  spin_until_readable(socket_);
  for (;;) {
    zmq::pollitem_t items[2] = {{socket_.handle(), 0, ZMQ_POLLIN, 0},
                                {watch_ ? watch_->events().handle() : nullptr, 0, ZMQ_POLLIN, 0}};
    zmq::pollitem_t& item = items[0];
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock::now());
    const auto slice = std::clamp(left, std::chrono::milliseconds(0), kPollSlice);
    const auto before = clock::now();
    try {
      zmq::poll(items, watch_ ? 2 : 1, slice);
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) throw ModuleFailure(name_, std::string("poll failed: ") + e.what());
      items[0].revents = items[1].revents = 0;  // a signal arrived: look at the hooks below
    }
    if (item.revents & ZMQ_POLLIN) break;
    // Before the first reply a drop is the handshake's (CURVE keys that do not match): the
    // timeout below names that. Once the session runs, a drop loses the request in flight.
    if ((items[1].revents & ZMQ_POLLIN) && watch_->take_disconnection() >= 0 && answered_) {
      throw ModuleFailure(name_, "the connection to " + endpoint_ + " dropped while the coupler "
                                 "waited for a reply (a TCP reset, the network or the module's "
                                 "host gone); the module ends its session when this happens: "
                                 "start it again and continue with `coupler resume OUT`");
    }
    // A wait far longer than asked for is time the coupler itself was not running (Ctrl-Z, a
    // laptop asleep): it does not count against the module.
    const auto overshoot = clock::now() - before - slice;
    if (overshoot > std::chrono::seconds(1)) deadline += overshoot;
    if (interruptible && hooks_.interrupted && hooks_.interrupted()) throw Interrupted();
    if (hooks_.dead) {
      if (auto why = hooks_.dead()) throw ModuleFailure(name_, "the process " + *why);
    }
    if (clock::now() >= deadline) {
      // A reply that arrived meanwhile is read, not lost to the deadline.
      zmq::pollitem_t last{socket_.handle(), 0, ZMQ_POLLIN, 0};
      try {
        zmq::poll(&last, 1, std::chrono::milliseconds(0));
      } catch (const zmq::error_t&) {
        last.revents = 0;
      }
      if (last.revents & ZMQ_POLLIN) break;
      const std::string within =
          std::to_string(timeout_.count() / 1000.0).substr(0, 6) + " s, the coupling timeout";
      if (curve_ && !answered_) {
        // ZeroMQ drops a CURVE handshake that fails authentication without a word to either
        // side: a first message unanswered is then most likely keys that do not match.
        throw ModuleFailure(name_, "never answered (no reply to the first message within " +
                                       within + "): with CURVE this is what keys that do not "
                                       "match look like: check that --curve-keys holds the "
                                       "module's server key and that the module was started "
                                       "with CURVE and its own keys (coupler keygen)");
      }
      throw ModuleFailure(name_, "stopped answering (no reply within " + within + ")");
    }
  }
  answered_ = true;
  try {
    reply.receive(socket_);
  } catch (const ProtocolError& e) {
    throw ModuleFailure(name_, std::string("sent a malformed message: ") + e.what());
  }
  if (reply.envelope.has_error()) {
    throw ModuleFailure(name_, reply.envelope.error().message(), /*refused=*/true);
  }
}

void ModuleClient::request(Message& request, Message& reply) {
  send(request);
  receive(reply);
}

}  // namespace rockcut::wire
