// The coupler's side of one module session: a REQ socket with a deadline on every answer.
//
// While waiting it polls in short slices so that a module process that died, a signal to the
// coupler, or a module that stays silent past the timeout is noticed and named.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <zmq.hpp>

#include "wire/connection_watch.hpp"
#include "wire/message.hpp"

namespace rockcut::wire {

/// A module failed: it died, stopped answering, or answered with an Error. what() is one line that
/// names the module.
class ModuleFailure : public std::runtime_error {
 public:
  /// `refused`: the module is alive and answered with an Error (e.g. it rejected the scene), as
  /// opposed to dying or falling silent.
  ModuleFailure(std::string module, const std::string& reason, bool refused = false)
      : std::runtime_error(module + ": " + reason), module_(std::move(module)), refused_(refused) {}
  const std::string& module() const { return module_; }
  bool refused() const { return refused_; }

 private:
  std::string module_;
  bool refused_;
};

/// The coupler was asked to stop (SIGINT/SIGTERM) while waiting.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted by signal") {}
};

struct ClientHooks {
  /// Returns why the module is gone (e.g. "killed by signal 9 (SIGKILL)"), or nothing if alive.
  std::function<std::optional<std::string>()> dead;
  /// True once the user asked the run to stop.
  std::function<bool()> interrupted;
};

/// A CURVE session (wire/curve_keys.hpp): the client's key pair and the server's public key, Z85.
struct CurveClientKeys {
  std::string public_key;
  std::string secret_key;
  std::string server_key;
};

class ModuleClient {
 public:
  ModuleClient(zmq::context_t& context, std::string module_name, const std::string& endpoint,
               std::chrono::milliseconds timeout, ClientHooks hooks,
               const std::optional<CurveClientKeys>& curve = std::nullopt);

  /// Sends a request; pair with receive(). Splitting the two lets the coupler overlap work.
  void send(Message& request);
  /// Waits for the answer. Throws ModuleFailure (dead, stalled past the timeout, Error reply,
  /// malformed reply) or, if `interruptible`, Interrupted.
  void receive(Message& reply, bool interruptible = true);
  /// send() then receive().
  void request(Message& request, Message& reply);

  const std::string& name() const { return name_; }
  void set_timeout(std::chrono::milliseconds timeout) { timeout_ = timeout; }

 private:
  std::string name_;
  zmq::socket_t socket_;
  std::chrono::milliseconds timeout_;
  ClientHooks hooks_;
  std::string endpoint_;
  /// tcp only: the connection dropping is named at once. Declared after socket_, so destroyed
  /// before it: the monitor stops while the socket it watches still exists.
  std::unique_ptr<ConnectionWatch> watch_;
  bool curve_ = false;     ///< a CURVE session
  bool answered_ = false;  ///< a reply has come: the CURVE handshake, if any, succeeded
};

}  // namespace rockcut::wire
