// The serving side of a module: one session on a REP socket, from Hello to Shutdown.
// dem_module and fluid_module implement ModuleHandler; the loop, the handshake and error replies
// are shared here so every module (built in or someone else's) behaves the same on the wire.
#pragma once

#include <string>
#include <vector>

#include <zmq.hpp>

#include "wire/message.hpp"

namespace rockcut::wire {

class ModuleHandler {
 public:
  virtual ~ModuleHandler() = default;
  virtual ModuleKind kind() const = 0;
  /// Executable/library name and version, reported in the handshake.
  virtual std::string name() const = 0;
  virtual std::string version() const = 0;
  /// Models (fluid) or physics (DEM) this module offers.
  virtual std::vector<std::string> models() const = 0;
  /// Answers every request after Hello (Init, Advance, ...). A thrown std::exception becomes an
  /// Error reply naming this module; the session then waits for Shutdown.
  virtual void handle(const Message& request, Message& reply) = 0;
  /// Runs after a reply has been sent and before the next request is read: work that the coupler
  /// does not wait for (the DEM computes its contact forces here while the fluid works).
  virtual void after_reply() {}
};

struct ServeOptions {
  /// Protocol version announced in the handshake (tests use another value to provoke a mismatch).
  unsigned protocol_version = 0;  // 0: the current kProtocolVersion
};

/// Binds `endpoint`, serves one session and returns after Shutdown. Returns 0 on a clean session.
/// Throws zmq::error_t if the endpoint cannot be bound.
int serve(zmq::context_t& context, const std::string& endpoint, ModuleHandler& handler,
          const ServeOptions& options = {});

}  // namespace rockcut::wire
