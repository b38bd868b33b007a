// A module session over inproc: handshake, Error replies, a silent module, a dead module.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "wire/module_client.hpp"
#include "wire/module_server.hpp"
#include "wire/protocol.hpp"

namespace rockcut::wire {
namespace {

using namespace std::chrono_literals;

class EchoHandler final : public ModuleHandler {
 public:
  ModuleKind kind() const override { return MODULE_KIND_FLUID; }
  std::string name() const override { return "echo"; }
  std::string version() const override { return "1.0"; }
  std::vector<std::string> models() const override { return {"echo"}; }
  void handle(const Message& request, Message& reply) override {
    if (request.envelope.has_fluid_step()) {
      if (request.envelope.fluid_step().dt_s() < 0) throw std::runtime_error("negative step");
      if (request.envelope.fluid_step().dt_s() > 100) std::this_thread::sleep_for(600ms);
      reply.envelope.mutable_fluid_result();
      reply.add_array("force", request.array("position", 2), 2);
      return;
    }
    reply.envelope.mutable_ack();
  }
  void after_reply() override { ++after_reply_calls; }
  std::atomic<int> after_reply_calls{0};
};

struct Session {
  zmq::context_t context{1};
  EchoHandler handler;
  std::thread server;
  std::unique_ptr<ModuleClient> client;
  explicit Session(std::chrono::milliseconds timeout, ServeOptions options = {}) {
    server = std::thread([this, options] {
      try {
        serve(context, "inproc://echo", handler, options);
      } catch (const zmq::error_t&) {
        // ETERM: the test ended the session by shutting the context down.
      }
    });
    client = std::make_unique<ModuleClient>(context, "echo", "inproc://echo", timeout, ClientHooks{});
    if (options.protocol_version == 0) {
      Message req, rep;
      req.envelope.mutable_hello()->set_protocol_version(kProtocolVersion);
      req.envelope.mutable_hello()->set_expected_kind(MODULE_KIND_FLUID);
      client->request(req, rep);
    }
  }
  ~Session() {
    context.shutdown();
    server.join();
  }
};

TEST(ClientServer, HandshakeReportsVersionKindAndModels) {
  ServeOptions options;
  options.protocol_version = kProtocolVersion;  // no Hello in the fixture
  Session s(2000ms, options);
  Message req, rep;
  req.envelope.mutable_hello()->set_protocol_version(kProtocolVersion);
  req.envelope.mutable_hello()->set_expected_kind(MODULE_KIND_FLUID);
  s.client->request(req, rep);
  ASSERT_TRUE(rep.envelope.has_hello_reply());
  EXPECT_EQ(rep.envelope.hello_reply().protocol_version(), kProtocolVersion);
  EXPECT_EQ(rep.envelope.hello_reply().kind(), MODULE_KIND_FLUID);
  EXPECT_EQ(rep.envelope.hello_reply().models(0), "echo");
}

TEST(ClientServer, ServeOptionsCanAnnounceAnotherVersion) {
  ServeOptions options;
  options.protocol_version = 999;
  Session s(2000ms, options);
  Message req, rep;
  req.envelope.mutable_hello()->set_protocol_version(999);
  req.envelope.mutable_hello()->set_expected_kind(MODULE_KIND_FLUID);
  s.client->request(req, rep);
  EXPECT_EQ(rep.envelope.hello_reply().protocol_version(), 999u);
}

TEST(ClientServer, HelloOfAnotherVersionOrKindIsRefusedAndTheRightOneStillWorks) {
  ServeOptions options;
  options.protocol_version = kProtocolVersion;  // no Hello in the fixture
  Session s(2000ms, options);
  Message req, rep;
  req.envelope.mutable_hello()->set_protocol_version(99);
  req.envelope.mutable_hello()->set_expected_kind(MODULE_KIND_FLUID);
  EXPECT_THROW(s.client->request(req, rep), ModuleFailure);
  EXPECT_NE(rep.envelope.error().message().find("protocol version mismatch"), std::string::npos);
  req.envelope.mutable_hello()->set_protocol_version(kProtocolVersion);
  req.envelope.mutable_hello()->set_expected_kind(MODULE_KIND_DEM);
  EXPECT_THROW(s.client->request(req, rep), ModuleFailure);
  EXPECT_NE(rep.envelope.error().message().find("expected a dem_module"), std::string::npos);
  req.clear();
  req.envelope.mutable_fluid_step()->set_dt_s(1.0);  // before any accepted Hello
  EXPECT_THROW(s.client->request(req, rep), ModuleFailure);
  req.clear();
  req.envelope.mutable_hello()->set_protocol_version(kProtocolVersion);
  req.envelope.mutable_hello()->set_expected_kind(MODULE_KIND_FLUID);
  s.client->request(req, rep);
  EXPECT_TRUE(rep.envelope.has_hello_reply());
  EXPECT_THROW(s.client->request(req, rep), ModuleFailure);  // Hello again
  EXPECT_NE(rep.envelope.error().message().find("Hello again"), std::string::npos);
}

TEST(ClientServer, ASecondClientIsRefusedAndTheOwnerKeepsItsSession) {
  Session s(2000ms);
  ModuleClient intruder(s.context, "intruder", "inproc://echo", 2000ms, ClientHooks{});
  Message req, rep;
  req.envelope.mutable_hello()->set_protocol_version(kProtocolVersion);
  req.envelope.mutable_hello()->set_expected_kind(MODULE_KIND_FLUID);
  EXPECT_THROW(intruder.request(req, rep), ModuleFailure);
  EXPECT_NE(rep.envelope.error().message().find("another coupler"), std::string::npos);
  req.clear();
  req.envelope.mutable_shutdown();
  EXPECT_THROW(intruder.request(req, rep), ModuleFailure);
  req.clear();
  std::vector<double> x = {1, 2};
  req.envelope.mutable_fluid_step()->set_dt_s(1.0);
  req.add_array("position", x, 2);
  s.client->request(req, rep);
  EXPECT_EQ(rep.array("force", 2)[1], 2.0);
}

TEST(ClientServer, ArraysGoThereAndBackAndAfterReplyRuns) {
  Session s(2000ms);
  Message req, rep;
  std::vector<double> x = {1, 2, 3, 4};
  req.envelope.mutable_fluid_step()->set_dt_s(1.0);
  req.add_array("position", x, 2);
  s.client->request(req, rep);
  const auto f = rep.array("force", 2);
  EXPECT_EQ(std::vector<double>(f.begin(), f.end()), x);
  req.clear();
  req.envelope.mutable_shutdown();
  s.client->request(req, rep);
  EXPECT_TRUE(rep.envelope.has_ack());
  EXPECT_EQ(s.handler.after_reply_calls.load(), 2);  // after Hello and the step; not Shutdown
}

TEST(ClientServer, HandlerExceptionBecomesModuleFailureNamingTheModule) {
  Session s(2000ms);
  Message req, rep;
  req.envelope.mutable_fluid_step()->set_dt_s(-1.0);
  try {
    s.client->request(req, rep);
    FAIL() << "no ModuleFailure";
  } catch (const ModuleFailure& e) {
    EXPECT_EQ(e.module(), "echo");
    EXPECT_NE(std::string(e.what()).find("negative step"), std::string::npos);
  }
}

TEST(ClientServer, SilentModuleIsReportedAfterTheTimeout) {
  Session s(200ms);
  Message req, rep;
  std::vector<double> x = {1, 2};
  req.envelope.mutable_fluid_step()->set_dt_s(1000.0);  // the handler sleeps 600 ms
  req.add_array("position", x, 2);
  const auto start = std::chrono::steady_clock::now();
  try {
    s.client->request(req, rep);
    FAIL() << "no ModuleFailure";
  } catch (const ModuleFailure& e) {
    EXPECT_NE(std::string(e.what()).find("stopped answering"), std::string::npos) << e.what();
  }
  const auto waited = std::chrono::steady_clock::now() - start;
  // The timeout, plus at most one 50 ms poll slice and scheduling slack.
  EXPECT_GE(waited, 200ms);
  EXPECT_LT(waited, 450ms);
}

TEST(ClientServer, DeadHookStopsTheWaitAtOnce) {
  zmq::context_t context(1);
  ClientHooks hooks;
  hooks.dead = [] { return std::optional<std::string>("exited with status 3"); };
  ModuleClient client(context, "ghost", "inproc://nobody", 10000ms, hooks);
  Message req, rep;
  req.envelope.mutable_hello();
  const auto start = std::chrono::steady_clock::now();
  try {
    client.request(req, rep);
    FAIL() << "no ModuleFailure";
  } catch (const ModuleFailure& e) {
    EXPECT_EQ(std::string(e.what()), "ghost: the process exited with status 3");
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 500ms);
}

}  // namespace
}  // namespace rockcut::wire
