// A peer of a module on a loopback tcp port, for the tests that treat a module as a server that
// must survive hostile or careless clients (wire_fuzz_test.cpp, wire_session_test.cpp): the module
// started by hand with --bind, a client that never blocks, and the messages they exchange.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <zmq.hpp>

#include "integration/process_helpers.hpp"
#include "rockcut/scene.pb.h"
#include "wire/curve_keys.hpp"
#include "wire/message.hpp"
#include "wire/protocol.hpp"

namespace rockcut::test {

/// How long a client waits for a module's reply by default.
inline constexpr std::chrono::milliseconds kReplyTimeout{5000};

/// Resident memory of `pid` [MiB] (VmRSS), -1 if unknown.
double rss_mib(pid_t pid);

// A module started by hand with --bind on a free loopback port.
struct Module {
  std::filesystem::path dir;
  std::string endpoint;
  Spawned process;
  std::unique_ptr<KillOnExit> guard;
  Module(const std::string& exe, const std::string& tag, std::vector<std::string> extra = {}) {
    dir = fresh_dir(tag);
    endpoint = "tcp://127.0.0.1:" + std::to_string(free_tcp_port());
    // ROCKCUT_TEST_MODULE_DIR: fuzz the modules of another build (e.g. ROCKCUT_SANITIZE's).
    const char* other = std::getenv("ROCKCUT_TEST_MODULE_DIR");
    std::vector<std::string> argv = {other ? std::string(other) + "/" + exe : bin(exe), "--bind",
                                     endpoint};
    argv.insert(argv.end(), extra.begin(), extra.end());
    process = spawn(argv, dir, tag);
    guard.reset(new KillOnExit{process.pid});  // no temporary: its destructor would kill
  }
  bool alive() const { return !wait_exit(process.pid, std::chrono::milliseconds(0)).has_value(); }
};

// A client that never blocks: DEALER with REQ's empty delimiter, replies waited for with a poll.
struct Client {
  zmq::context_t context{1};
  zmq::socket_t socket{context, zmq::socket_type::dealer};
  explicit Client(const std::string& endpoint, const wire::CurveKeyPair* own = nullptr,
                  const std::string& server_key = "") {
    socket.set(zmq::sockopt::linger, 0);
    // A DEALER blocks in send while it has no peer, which a refused CURVE handshake can leave it
    // without: give up after a while instead of hanging the test.
    socket.set(zmq::sockopt::sndtimeo, 2000);
    if (own) {
      socket.set(zmq::sockopt::curve_serverkey, server_key);
      socket.set(zmq::sockopt::curve_publickey, own->public_key);
      socket.set(zmq::sockopt::curve_secretkey, own->secret_key);
    }
    socket.connect(endpoint);
  }
  void send_frames(std::vector<std::string> frames) {
    frames.insert(frames.begin(), std::string());
    for (std::size_t k = 0; k < frames.size(); ++k) {
      zmq::message_t m(frames[k].data(), frames[k].size());
      socket.send(m, k + 1 < frames.size() ? zmq::send_flags::sndmore : zmq::send_flags::none);
    }
  }
  /// False if the message could not be handed to the socket (no peer within the send timeout).
  bool send(wire::Message& message) {
    zmq::message_t empty;
    if (!socket.send(empty, zmq::send_flags::sndmore)) return false;
    message.send(socket);
    return true;
  }
  // The reply, or nothing within `timeout`.
  std::optional<wire::Message> receive(std::chrono::milliseconds timeout = kReplyTimeout) {
    zmq::pollitem_t item{socket.handle(), 0, ZMQ_POLLIN, 0};
    if (zmq::poll(&item, 1, timeout) <= 0) return std::nullopt;
    zmq::message_t empty;
    (void)socket.recv(empty);
    zmq::message_t head;
    (void)socket.recv(head);
    wire::Message reply;
    reply.receive_body(socket, head);
    return reply;
  }
  std::optional<wire::Message> request(wire::Message& message,
                                       std::chrono::milliseconds timeout = kReplyTimeout) {
    if (!send(message)) return std::nullopt;
    return receive(timeout);
  }
};

/// A Hello asking for a module of `kind` with protocol `version`.
wire::Message hello(wire::ModuleKind kind, unsigned version = wire::kProtocolVersion);
/// A small dry scene: a 30 x 30 lattice falling freely.
rockcut::Scene tiny_scene();
/// The DEM's Init of `scene`.
wire::Message init_of(const rockcut::Scene& scene, const std::string& scene_dir = "");
/// The fluid's Init of `scene`, with the solid properties of the DEM's reply `dem`.
wire::Message fluid_init_of(const rockcut::Scene& scene, const wire::InitReply& dem);
/// The Init of a module of `kind`.
wire::Message init_for(wire::ModuleKind kind, const rockcut::Scene& scene,
                       const std::string& scene_dir, const wire::InitReply& dem);
/// The text of an Error reply, or why there is none.
std::string error_of(const std::optional<wire::Message>& reply);
/// Ends the owner's session and expects a clean exit of the module.
void shut_down(Client& owner, Module& module);

}  // namespace rockcut::test
