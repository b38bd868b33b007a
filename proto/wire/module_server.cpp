#include "wire/module_server.hpp"

#include <chrono>
#include <exception>

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

}  // namespace

int serve(zmq::context_t& context, const std::string& endpoint, ModuleHandler& handler,
          const ServeOptions& options) {
  zmq::socket_t socket(context, zmq::socket_type::rep);
  socket.set(zmq::sockopt::linger, 0);
  socket.bind(endpoint);
  const unsigned version = options.protocol_version ? options.protocol_version : kProtocolVersion;

  Message request;
  Message reply;
  // Over ipc:// the replies' large arrays go through shared memory (wire/shared_payload.hpp).
  const std::unique_ptr<SharedPayloadArena> arena = SharedPayloadArena::for_endpoint(endpoint);
  reply.use_arena(arena.get());
  using clock = std::chrono::steady_clock;
  double busy_s = 0.0;   // handling time, reported in every reply's Envelope.busy_s
  double after_s = 0.0;  // the part of it after replying (Envelope.after_reply_s)
  for (;;) {
    spin_until_readable(socket);
    request.receive(socket);
    const auto start = clock::now();
    reply.clear();
    const Envelope::BodyCase body = request.envelope.body_case();
    if (body == Envelope::kShutdown) {
      reply.envelope.mutable_ack();
      reply.send(socket);
      return 0;
    }
    if (body == Envelope::kHello) {
      fill_hello_reply(handler, version, *reply.envelope.mutable_hello_reply());
    } else {
      try {
        handler.handle(request, reply);
      } catch (const std::exception& e) {
        reply.clear();
        Error* error = reply.envelope.mutable_error();
        error->set_module(handler.name());
        error->set_message(e.what());
      }
    }
    busy_s += std::chrono::duration<double>(clock::now() - start).count();
    reply.envelope.set_busy_s(busy_s);
    reply.envelope.set_after_reply_s(after_s);
    reply.send(socket);
    const auto after = clock::now();
    handler.after_reply();
    const double after_reply = std::chrono::duration<double>(clock::now() - after).count();
    busy_s += after_reply;
    after_s += after_reply;
  }
}

}  // namespace rockcut::wire
