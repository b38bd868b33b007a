#include "wire/module_server.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <exception>
#include <iostream>
#include <thread>

#include "wire/connection_watch.hpp"
#include "wire/protocol.hpp"
#include "wire/shared_payload.hpp"
#include "wire/spin_wait.hpp"

namespace rockcut::wire {

namespace {

void fill_hello_reply(const ModuleHandler& handler, unsigned version, HelloReply& reply) {
  reply.set_protocol_version(version);
  reply.set_kind(handler.kind());
  reply.set_module_name(handler.name());
  reply.set_module_version(handler.version());
  for (const std::string& m : handler.models()) reply.add_models(m);
}

// Drops the rest of a multipart message.
void drain(zmq::socket_t& socket, bool more) {
  while (more) {
    zmq::message_t part;
    receive_part(socket, part);
    more = part.more();
  }
}

// The ZAP handler (RFC 27) of a CURVE server: accepts the one client key it was given. It runs
// on its own thread because libzmq asks it while a connection is made, whatever the serving
// thread is doing.
class ZapHandler {
 public:
  ZapHandler(zmq::context_t& context, const std::string& client_key_z85)
      : socket_(context, zmq::socket_type::rep) {
    if (client_key_z85.size() != 40 || !zmq_z85_decode(client_key_, client_key_z85.c_str())) {
      throw std::invalid_argument("the client's CURVE public key is not 40 Z85 characters");
    }
    socket_.set(zmq::sockopt::linger, 0);
    socket_.bind("inproc://zeromq.zap.01");
    thread_ = std::thread([this] { run(); });
  }
  ~ZapHandler() {
    stop_ = true;
    thread_.join();
  }

 private:
  void run() {
    while (!stop_) {
      zmq::pollitem_t item{socket_.handle(), 0, ZMQ_POLLIN, 0};
      try {
        zmq::poll(&item, 1, std::chrono::milliseconds(100));
        if (!(item.revents & ZMQ_POLLIN)) continue;
        std::vector<zmq::message_t> parts;
        bool more = true;
        while (more) {
          zmq::message_t part;
          receive_part(socket_, part);
          more = part.more();
          if (parts.size() < 16) parts.push_back(std::move(part));
        }
        // version, request id, domain, address, routing id, mechanism, credentials...
        const bool ok = parts.size() >= 7 && parts[5].to_string_view() == "CURVE" &&
                        parts[6].size() == 32 && std::memcmp(parts[6].data(), client_key_, 32) == 0;
        const std::string request_id = parts.size() > 1 ? parts[1].to_string() : "";
        const std::string replies[] = {"1.0", request_id, ok ? "200" : "400",
                                       ok ? "OK" : "not the coupler's key", "", ""};
        for (std::size_t k = 0; k < 6; ++k) {
          zmq::message_t out(replies[k].data(), replies[k].size());
          socket_.send(out, k + 1 < 6 ? zmq::send_flags::sndmore : zmq::send_flags::none);
        }
      } catch (const zmq::error_t&) {
        return;  // the context is ending
      }
    }
  }

  zmq::socket_t socket_;
  std::uint8_t client_key_[32] = {};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Whether any array of `message` points into shared memory.
bool names_shared_memory(const Message& message) {
  for (const ArrayHeader& h : message.envelope.arrays()) {
    if (!h.shared_segment().empty()) return true;
  }
  return false;
}

}  // namespace

int serve(zmq::context_t& context, const std::string& endpoint, ModuleHandler& handler,
          const ServeOptions& options) {
  std::unique_ptr<ZapHandler> zap;
  if (!options.curve_secret_key.empty()) zap = std::make_unique<ZapHandler>(context, options.curve_client_key);
  // ROUTER rather than REP: every message comes with its sender, so the session keeps to one
  // client and a malformed message is answered without breaking REP's strict alternation.
  zmq::socket_t socket(context, zmq::socket_type::router);
  socket.set(zmq::sockopt::linger, 0);
  socket.set(zmq::sockopt::maxmsgsize, options.max_message_bytes);
  if (zap) {
    socket.set(zmq::sockopt::curve_server, 1);
    socket.set(zmq::sockopt::curve_secretkey, options.curve_secret_key);
    socket.set(zmq::sockopt::zap_domain, "rockcut");
  }
  socket.bind(endpoint);
  // Over tcp a session ends when its coupler's connection drops: ZeroMQ would reconnect it as
  // another client, which the session refuses, so the module would stay up serving no one.
  std::unique_ptr<ConnectionWatch> watch;
  if (endpoint.starts_with("tcp://")) watch = std::make_unique<ConnectionWatch>(context, socket);
  int owner_fd = -1;  // the connection the session's Hello came in on
  const unsigned version = options.protocol_version ? options.protocol_version : kProtocolVersion;
  // Shared-memory segments are named by local peers only (wire/shared_payload.hpp).
  const bool shared_memory_allowed = endpoint.starts_with("ipc://");

  Message request;
  Message reply;
  // Over ipc:// the replies' large arrays go through shared memory (wire/shared_payload.hpp).
  const std::unique_ptr<SharedPayloadArena> arena = SharedPayloadArena::for_endpoint(endpoint);
  reply.use_arena(arena.get());
  using clock = std::chrono::steady_clock;
  double busy_s = 0.0;   // handling time, reported in every reply's Envelope.busy_s
  double after_s = 0.0;  // the part of it after replying (Envelope.after_reply_s)
  std::string owner;     // routing id of the client whose Hello opened the session
  bool initialised = false;
  const std::string module = handler.name();
  for (;;) {
    spin_until_readable(socket);
    if (watch) {
      zmq::pollitem_t items[2] = {{socket.handle(), 0, ZMQ_POLLIN, 0},
                                  {watch->events().handle(), 0, ZMQ_POLLIN, 0}};
      try {
        zmq::poll(items, 2, std::chrono::milliseconds(-1));
      } catch (const zmq::error_t& e) {
        if (e.num() == EINTR) continue;
        throw;
      }
      if (items[1].revents & ZMQ_POLLIN) {
        const int dropped = watch->take_disconnection();
        if (owner_fd >= 0 && dropped == owner_fd) {
          std::cerr << module << ": the connection of the coupler that owned the session dropped "
                       "(a TCP reset or its host gone); session ended\n";
          return 3;
        }
      }
      if (!(items[0].revents & ZMQ_POLLIN)) continue;
    }
    zmq::message_t peer_id;
    receive_part(socket, peer_id);
    if (!peer_id.more()) continue;
    zmq::message_t delimiter;
    receive_part(socket, delimiter);
    if (delimiter.size() != 0 || !delimiter.more()) {
      drain(socket, delimiter.more());  // not a REQ client: nothing to answer
      continue;
    }
    zmq::message_t head;
    receive_part(socket, head);
    const int head_fd = watch ? source_fd(head) : -1;
    const auto start = clock::now();
    reply.clear();
    const std::string peer = peer_id.to_string();
    std::string refusal;
    try {
      request.receive_body(socket, head);
    } catch (const ProtocolError& e) {
      refusal = std::string("malformed request: ") + e.what();
    }
    const Envelope::BodyCase body = request.envelope.body_case();
    const bool from_owner = !owner.empty() && peer == owner;
    bool shutdown = false;
    if (!refusal.empty()) {
      // answered below
    } else if (!owner.empty() && !from_owner) {
      refusal = "serves another coupler's session; start a module of your own";
    } else if (body == Envelope::kHello) {
      const Hello& hello = request.envelope.hello();
      if (from_owner) {
        refusal = "Hello again: the session is open already";
      } else if (hello.protocol_version() != version) {
        refusal = "protocol version mismatch: the coupler " + hello.coupler_version().substr(0, 40) +
                  " speaks protocol " + std::to_string(hello.protocol_version()) + ", " + module +
                  " " + handler.version() + " speaks protocol " + std::to_string(version) +
                  "; rebuild both from the same source, or point the scene at a matching executable";
      } else if (hello.expected_kind() != handler.kind()) {
        refusal = "the coupler expected a " + std::string(kind_name(hello.expected_kind())) +
                  ", but " + module + " " + handler.version() + " is a " +
                  std::string(kind_name(handler.kind()));
      } else {
        owner = peer;
        owner_fd = head_fd;
        fill_hello_reply(handler, version, *reply.envelope.mutable_hello_reply());
      }
    } else if (owner.empty()) {
      refusal = "a session starts with Hello";
    } else if (body == Envelope::kShutdown) {
      reply.envelope.mutable_ack();
      shutdown = true;
    } else if (body == Envelope::kInit && initialised) {
      refusal = "Init again: a module serves one run; start a new module for another";
    } else if (!shared_memory_allowed && names_shared_memory(request)) {
      refusal = "arrays in shared memory are refused on " + endpoint.substr(0, 6) +
                " (only a peer on this host, over ipc://, may name them)";
    } else {
      initialised = initialised || body == Envelope::kInit;
      try {
        handler.handle(request, reply);
        if (reply.envelope.has_init_reply()) {
          // Connections made from now on get a bound derived from the particle count.
          const auto n = static_cast<std::int64_t>(
              std::min<std::uint64_t>(reply.envelope.init_reply().particle_count(), 1ull << 40));
          socket.set(zmq::sockopt::maxmsgsize,
                     std::min(options.max_message_bytes,
                              std::max(kMinMessageBytes, n * kBytesPerParticle)));
        }
      } catch (const std::exception& e) {
        refusal = e.what();
      }
    }
    if (!refusal.empty()) {
      reply.clear();
      Error* error = reply.envelope.mutable_error();
      error->set_module(module);
      error->set_message(refusal);
    }
    busy_s += std::chrono::duration<double>(clock::now() - start).count();
    reply.envelope.set_busy_s(busy_s);
    reply.envelope.set_after_reply_s(after_s);
    send_part(socket, peer_id, zmq::send_flags::sndmore);
    zmq::message_t empty;
    send_part(socket, empty, zmq::send_flags::sndmore);
    reply.send(socket);
    if (shutdown) return 0;
    if (peer != owner) continue;  // after_reply is the session's work only
    const auto after = clock::now();
    handler.after_reply();
    const double after_reply = std::chrono::duration<double>(clock::now() - after).count();
    busy_s += after_reply;
    after_s += after_reply;
  }
}

}  // namespace rockcut::wire
