// The serving side of a module: one session on a REP socket, from Hello to Shutdown.
// dem_module and fluid_module implement ModuleHandler; the loop, the handshake and error replies
// are shared here so every module (built in or someone else's) behaves the same on the wire.
#pragma once

#include <filesystem>

#include <cstdint>
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
  /// Over tcp the peer is not the module's own child-of coupler: files a peer names (the DEM's
  /// packing file) are read only under `root` (`--read-under`, default the module's working
  /// directory). Not called for ipc, whose private socket only the module's coupler reaches.
  virtual void set_read_root(const std::filesystem::path& /*root*/) {}
};

/// The largest ZeroMQ frame a module takes (ZMQ_MAXMSGSIZE): one array of a State of
/// scene::kMaxParticles particles at up to 32 doubles each (bonds, contacts). A peer announcing
/// more is disconnected by ZeroMQ before anything is buffered. After Init, connections made later
/// get kBytesPerParticle per particle (at least kMinMessageBytes, at most this).
inline constexpr std::int64_t kMaxMessageBytesBeforeInit = std::int64_t{512} << 20;
inline constexpr std::int64_t kBytesPerParticle = 512;
inline constexpr std::int64_t kMinMessageBytes = std::int64_t{16} << 20;

struct ServeOptions {
  /// Protocol version announced in the handshake (tests use another value to provoke a mismatch).
  unsigned protocol_version = 0;  // 0: the current kProtocolVersion
  /// CURVE (wire/curve_keys.hpp): the module's own secret key and the one client public key it
  /// accepts (Z85). Empty: no authentication or encryption (the default, for loopback).
  std::string curve_secret_key;
  std::string curve_client_key;
  std::int64_t max_message_bytes = kMaxMessageBytesBeforeInit;
};

/// Binds `endpoint`, serves one session and returns after Shutdown. Returns 0 on a clean session.
/// Throws zmq::error_t if the endpoint cannot be bound.
///
/// The session belongs to the first client whose Hello is accepted (right protocol version and
/// module kind); every message of any other client, and anything before that Hello, is answered
/// with an Error and otherwise ignored. A malformed message (frame 0 not an Envelope, array
/// frames other than announced, a shared-memory segment named over tcp) is answered with an
/// Error too; so are a second Hello or Init. The module keeps serving its coupler in all cases.
/// Over tcp the session ends, returning 3, when the connection its Hello came in on drops (a TCP
/// reset, the coupler's host gone): ZeroMQ would reconnect the coupler as another client, which
/// the session refuses.
int serve(zmq::context_t& context, const std::string& endpoint, ModuleHandler& handler,
          const ServeOptions& options = {});

}  // namespace rockcut::wire
