#include "run/module_link.hpp"

#include <stdexcept>

#include "run/signals.hpp"
#include "wire/curve_keys.hpp"
#include "wire/inproc_registry.hpp"
#include "wire/protocol.hpp"
#include "wire/shared_payload.hpp"

namespace rockcut::coupler {

const char* transport_name(Transport t) {
  switch (t) {
    case Transport::ipc: return "ipc";
    case Transport::inproc: return "inproc";
    case Transport::tcp: return "tcp";
  }
  return "?";
}

ModuleLink::ModuleLink(zmq::context_t& context, const LinkSpec& spec) : spec_(spec) {
  const std::string kind(wire::kind_name(spec.kind));
  switch (spec.transport) {
    case Transport::ipc:
      process_ = std::make_unique<ChildProcess>(spec.executable,
                                                std::vector<std::string>{"--bind", spec.endpoint});
      label_ = spec.executable.filename().string() + " (pid " + std::to_string(process_->pid()) + ")";
      break;
    case Transport::inproc: {
      wire::InprocServeFn serve = wire::find_inproc_module(spec.kind);
      if (!serve) throw std::runtime_error("no built-in " + kind + " is linked into the coupler");
      label_ = kind + " (inproc thread)";
      thread_ = std::thread([this, serve, &context] {
        try {
          serve(context, spec_.endpoint);
        } catch (const zmq::error_t& e) {
          if (e.num() != ETERM) thread_error_ = e.what();
        } catch (const std::exception& e) {
          thread_error_ = e.what();
        }
        thread_done_ = true;
      });
      break;
    }
    case Transport::tcp:
      label_ = kind + " at " + spec.endpoint;
      break;
  }
  wire::ClientHooks hooks;
  hooks.dead = [this] { return dead(); };
  hooks.interrupted = [] { return interrupt_now(); };
  std::optional<wire::CurveClientKeys> curve;
  if (!spec.curve_keys.empty()) {
    // The coupler's own pair, and the module's public key: a server without it cannot answer.
    const wire::CurveKeyPair own = wire::read_key_pair(spec.curve_keys, "coupler");
    curve = wire::CurveClientKeys{own.public_key, own.secret_key,
                                  wire::read_public_key(spec.curve_keys, kind)};
  }
  client_ = std::make_unique<wire::ModuleClient>(context, label_, spec.endpoint, spec.timeout,
                                                 std::move(hooks), curve);
}

ModuleLink::~ModuleLink() {
  close();
  if (thread_.joinable()) thread_.join();
}

std::optional<std::string> ModuleLink::dead() {
  if (process_) return process_->ended();
  if (thread_done_) {
    return std::optional<std::string>("thread ended" +
                                      (thread_error_.empty() ? "" : ": " + thread_error_));
  }
  return std::nullopt;
}

void ModuleLink::send(wire::Message& request) {
  client_->send(request);
  awaiting_reply_ = true;
}

void ModuleLink::receive(wire::Message& reply) {
  try {
    client_->receive(reply);
    awaiting_reply_ = false;
  } catch (const wire::ModuleFailure& e) {
    // An Error reply leaves the session usable (the module waits for Shutdown); silence or death
    // does not.
    if (reply.envelope.has_error()) {
      awaiting_reply_ = false;
    } else {
      failed_ = true;
    }
    throw;
  }
}

void ModuleLink::request(wire::Message& request, wire::Message& reply) {
  const auto start = std::chrono::steady_clock::now();
  send(request);
  receive(reply);
  request_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

wire::HelloReply ModuleLink::handshake() {
  wire::Message request, reply;
  wire::Hello* hello = request.envelope.mutable_hello();
  hello->set_protocol_version(wire::kProtocolVersion);
  hello->set_expected_kind(spec_.kind);
  hello->set_coupler_version(ROCKCUT_VERSION);
  try {
    this->request(request, reply);
  } catch (const wire::ModuleFailure& e) {
    // A module that refuses the handshake (another protocol version or kind) is the wrong
    // module, not a refused scene.
    if (!e.refused()) throw;
    throw wire::ModuleFailure(label_, reply.envelope.error().message());
  }
  if (!reply.envelope.has_hello_reply()) {
    throw wire::ModuleFailure(label_, "did not answer the handshake with HelloReply");
  }
  const wire::HelloReply& r = reply.envelope.hello_reply();
  const std::string them = r.module_name() + " " + r.module_version();
  if (r.protocol_version() != wire::kProtocolVersion) {
    throw wire::ModuleFailure(
        label_, "protocol version mismatch: the coupler " ROCKCUT_VERSION " speaks protocol " +
                    std::to_string(wire::kProtocolVersion) + ", " + them + " speaks protocol " +
                    std::to_string(r.protocol_version()) +
                    "; rebuild both from the same source, or point the scene at a matching "
                    "executable");
  }
  if (r.kind() != spec_.kind) {
    throw wire::ModuleFailure(label_, "the coupler expected a " +
                                          std::string(wire::kind_name(spec_.kind)) + ", but " +
                                          them + " is a " +
                                          std::string(wire::kind_name(r.kind())));
  }
  return r;
}

void ModuleLink::close() {
  if (closed_) return;
  closed_ = true;
  try {
    client_->set_timeout(std::chrono::milliseconds(2000));
    wire::Message request, reply;
    if (!failed_ && awaiting_reply_) {
      // Interrupted while the module worked: collect its answer so the session can end politely.
      client_->receive(reply, /*interruptible=*/false);
      awaiting_reply_ = false;
    }
    if (!failed_) {
      request.envelope.mutable_shutdown();
      client_->send(request);
      client_->receive(reply, /*interruptible=*/false);
    }
  } catch (const std::exception&) {
    // Already failing: the process is stopped below.
  }
  client_.reset();  // closes the socket (linger 0)
  if (process_) {
    process_->stop(std::chrono::milliseconds(2000));
    // A module that was killed could not unlink its shared-memory arrays (wire/shared_payload.hpp).
    wire::remove_shared_segments_of(process_->pid());
  }
  // A module thread still blocked in recv is released by the owner's context.shutdown(), after
  // which the destructor joins it.
  if (thread_.joinable() && thread_done_) thread_.join();
}

}  // namespace rockcut::coupler
