// One module as the coupler sees it: how it was started (child process over ipc, thread over
// inproc, or attached over tcp), the session with it, and how to end it.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include <zmq.hpp>

#include "process/child_process.hpp"
#include "wire/module_client.hpp"

namespace rockcut::coupler {

enum class Transport { ipc, inproc, tcp };

const char* transport_name(Transport t);

struct LinkSpec {
  wire::ModuleKind kind = wire::MODULE_KIND_UNSPECIFIED;
  Transport transport = Transport::ipc;
  std::string endpoint;               ///< where the module serves
  std::filesystem::path executable;   ///< ipc only: the program to start
  std::chrono::milliseconds timeout{30000};
  /// tcp only: key directory for a CURVE session (wire/curve_keys.hpp); empty: plain tcp.
  std::filesystem::path curve_keys;
};

class ModuleLink {
 public:
  /// Starts (ipc, inproc) or attaches to (tcp) the module. Throws std::runtime_error if it cannot.
  ModuleLink(zmq::context_t& context, const LinkSpec& spec);
  ~ModuleLink();

  /// "dem_module (pid 123)", "fluid_module (thread)", "dem_module at tcp://..." for messages.
  const std::string& label() const { return label_; }

  /// Hello: checks protocol version and kind, names both sides on a mismatch (ModuleFailure).
  wire::HelloReply handshake();

  void send(wire::Message& request);
  void receive(wire::Message& reply);
  void request(wire::Message& request, wire::Message& reply);
  /// Wall time the coupler has spent in request() on this link: the module's handling, the
  /// transport, and waiting for the module (e.g. its work after its last reply) [s].
  double request_s() const { return request_s_; }

  /// Ends the session: Shutdown if the module can still answer, then waits for the process or
  /// thread; kills a process that does not end. Never throws.
  void close();

  void set_timeout(std::chrono::milliseconds t) { client_->set_timeout(t); }

 private:
  std::optional<std::string> dead();

  LinkSpec spec_;
  std::string label_;
  double request_s_ = 0.0;
  std::unique_ptr<ChildProcess> process_;
  std::thread thread_;
  std::atomic<bool> thread_done_{false};
  std::string thread_error_;
  std::unique_ptr<wire::ModuleClient> client_;
  bool awaiting_reply_ = false;
  bool failed_ = false;
  bool closed_ = false;
};

}  // namespace rockcut::coupler
