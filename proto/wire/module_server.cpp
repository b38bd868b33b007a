#include "wire/module_server.hpp"

#include <exception>

#include "wire/protocol.hpp"

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
  for (;;) {
    request.receive(socket);
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
    reply.send(socket);
    handler.after_reply();
  }
}

}  // namespace rockcut::wire
