#include "integration/wire_peer.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "scene/scene_loader.hpp"
#include "wire/init_parts.hpp"

namespace rockcut::test {

using namespace std::chrono_literals;
using wire::Message;

double rss_mib(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (in >> key) {
    if (key == "VmRSS:") {
      double kib = 0;
      in >> kib;
      return kib / 1024.0;
    }
  }
  return -1;
}

Message hello(wire::ModuleKind kind, unsigned version) {
  Message m;
  m.envelope.mutable_hello()->set_protocol_version(version);
  m.envelope.mutable_hello()->set_expected_kind(kind);
  return m;
}

rockcut::Scene tiny_scene() {
  return scene::load_scene(source("cases/verification/free_fall.pbtxt"), {}).scene;
}

Message init_of(const rockcut::Scene& scene, const std::string& scene_dir) {
  Message m;
  wire::set_dem_part(scene, scene_dir, *m.envelope.mutable_init());
  return m;
}

Message fluid_init_of(const rockcut::Scene& scene, const wire::InitReply& dem) {
  Message m;
  wire::set_fluid_part(scene, dem, *m.envelope.mutable_init());
  return m;
}

Message init_for(wire::ModuleKind kind, const rockcut::Scene& scene, const std::string& scene_dir,
                 const wire::InitReply& dem) {
  return kind == wire::MODULE_KIND_FLUID ? fluid_init_of(scene, dem) : init_of(scene, scene_dir);
}

std::string error_of(const std::optional<Message>& reply) {
  if (!reply) return "<no reply>";
  return reply->envelope.has_error() ? reply->envelope.error().message() : "<not an Error>";
}

void shut_down(Client& owner, Module& module) {
  Message m;
  m.envelope.mutable_shutdown();
  const auto reply = owner.request(m);
  ASSERT_TRUE(reply && reply->envelope.has_ack());
  EXPECT_EQ(wait_exit(module.process.pid, 5000ms), 0);
}

}  // namespace rockcut::test
