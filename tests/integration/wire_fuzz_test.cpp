// A module on a loopback tcp port against a hostile peer: malformed, random and mutated wire
// messages, random bytes on a raw TCP connection, a frame announcing 3 GiB. Each case asserts
// that the module is not killed by a signal, answers within a timeout (an Error or a dropped
// connection), keeps its memory bounded and keeps serving its own coupler, which ends the
// session cleanly (exit 0). Bad Inits, a second client and CURVE: wire_session_test.cpp.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <random>

#include <zmq.hpp>

#include "integration/process_helpers.hpp"
#include "integration/wire_peer.hpp"
#include "scene/scene_loader.hpp"
#include "wire/message.hpp"
#include "wire/protocol.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using wire::Message;

TEST(WireFuzz, MalformedMessagesGetAnErrorAndTheSessionGoesOn) {
  Module dem("dem_module", "malformed");
  Client owner(dem.endpoint);
  Message h = hello(wire::MODULE_KIND_DEM);
  ASSERT_TRUE(owner.request(h)->envelope.has_hello_reply());

  owner.send_frames({"this is not an envelope \xff\xff\xff"});
  EXPECT_NE(error_of(owner.receive()).find("not a rockcut.wire.Envelope"), std::string::npos);

  Message two;  // announces two arrays, sends none
  two.envelope.mutable_frame_request();
  two.envelope.add_arrays()->set_name("a");
  two.envelope.add_arrays()->set_name("b");
  owner.send_frames({two.envelope.SerializeAsString()});
  EXPECT_NE(error_of(owner.receive()).find("announces 2 arrays, 0 frames"), std::string::npos);
  owner.send_frames({Message().envelope.SerializeAsString(), "x", "y", "z"});
  EXPECT_NE(error_of(owner.receive()).find("announces 0 arrays, 3 frames"), std::string::npos);

  ASSERT_TRUE(owner.request(*std::make_unique<Message>(init_of(tiny_scene())))->envelope.has_init_reply());
  // An array whose count * 2 * 8 bytes wraps around to the 16 bytes sent.
  Message wrap;
  wrap.envelope.mutable_apply_forces();
  std::vector<double> two_values = {1.0, 2.0};
  wrap.add_array("force", two_values, 2);
  wrap.envelope.mutable_arrays(0)->set_count((std::uint64_t{1} << 60) + 1);
  EXPECT_NE(error_of(owner.request(wrap)).find("array 'force'"), std::string::npos);
  // Over tcp no peer may name a shared-memory segment.
  Message shm;
  shm.envelope.mutable_apply_forces();
  shm.add_array("force", two_values, 2);
  shm.envelope.mutable_arrays(0)->set_shared_segment("/rockcut.1.0-1.force.0.v1");
  EXPECT_NE(error_of(owner.request(shm)).find("shared memory"), std::string::npos);
  Message again = init_of(tiny_scene());
  EXPECT_NE(error_of(owner.request(again)).find("Init again"), std::string::npos);
  Message again_hello = hello(wire::MODULE_KIND_DEM);
  EXPECT_NE(error_of(owner.request(again_hello)).find("Hello again"), std::string::npos);

  Message advance;
  advance.envelope.mutable_advance()->set_steps(10);
  advance.envelope.mutable_advance()->set_dt_s(2e-5);
  const auto report = owner.request(advance);
  ASSERT_TRUE(report && report->envelope.has_step_report()) << error_of(report);
  EXPECT_EQ(report->envelope.step_report().step(), 10u);
  shut_down(owner, dem);
}

TEST(WireFuzz, HelloOfAnotherVersionOrKindIsRefused) {
  Module fluid("fluid_module", "hello");
  Client client(fluid.endpoint);
  Message v99 = hello(wire::MODULE_KIND_FLUID, 99);
  EXPECT_NE(error_of(client.request(v99)).find("protocol version mismatch"), std::string::npos);
  Message dem = hello(wire::MODULE_KIND_DEM);
  EXPECT_NE(error_of(client.request(dem)).find("expected a dem_module"), std::string::npos);
  Message early = init_of(tiny_scene());
  EXPECT_NE(error_of(client.request(early)).find("starts with Hello"), std::string::npos);
  Message right = hello(wire::MODULE_KIND_FLUID);
  ASSERT_TRUE(client.request(right)->envelope.has_hello_reply());
  shut_down(client, fluid);
}

// The number of mutated messages per module and the seed: ROCKCUT_FUZZ_MESSAGES and
// ROCKCUT_FUZZ_SEED run a larger corpus by hand (the default is a few seconds in ctest).
int fuzz_messages() {
  const char* n = std::getenv("ROCKCUT_FUZZ_MESSAGES");
  return n ? std::atoi(n) : 400;
}
std::uint64_t fuzz_seed() {
  const char* n = std::getenv("ROCKCUT_FUZZ_SEED");
  return n ? std::strtoull(n, nullptr, 10) : 20261124;
}

// The arrays a DEM module gives for the saturated reduced cut (its own Init, then a FrameRequest),
// and its InitReply in `dem_reply`.
Message dem_arrays(const rockcut::Scene& scene, const std::string& scene_dir,
                   const std::vector<std::string>& fields, wire::InitReply& dem_reply) {
  Module dem("dem_module", "arrays_dem");
  Client client(dem.endpoint);
  Message h = hello(wire::MODULE_KIND_DEM);
  EXPECT_TRUE(client.request(h)->envelope.has_hello_reply());
  Message init = init_of(scene, scene_dir);
  const std::optional<Message> init_reply = client.request(init, 20000ms);
  EXPECT_TRUE(init_reply && init_reply->envelope.has_init_reply());
  if (init_reply) dem_reply = init_reply->envelope.init_reply();
  Message frame;
  for (const std::string& f : fields) frame.envelope.mutable_frame_request()->add_fields(f);
  std::optional<Message> reply = client.request(frame);
  EXPECT_TRUE(reply && reply->envelope.has_frame()) << error_of(reply);
  shut_down(client, dem);
  return std::move(*reply);
}

// Copies `from`'s arrays `names` into `to`.
void copy_arrays(const Message& from, const std::vector<std::string>& names, Message& to) {
  for (const std::string& name : names) {
    for (const wire::ArrayHeader& h : from.envelope.arrays()) {
      if (h.name() == name) to.add_array(name, from.array(name, h.components()), h.components());
    }
  }
}

// Valid envelopes of every request, then mutated: bytes flipped, cut short, grown, array headers
// with made-up counts and too few or too many frames. The module (initialised with the saturated
// reduced cut, so the fluid's step runs) must answer each one.
TEST(WireFuzz, RandomAndMutatedMessagesNeverKillOrWedgeTheModule) {
  const std::string scene_dir = source("cases/cutting");
  const rockcut::Scene scene = scene::load_scene(scene_dir + "/saturated_reduced.pbtxt", {}).scene;
  const std::vector<std::string> kinematics = {"position", "velocity_half", "displacement",
                                               "wall_segments"};
  std::vector<std::string> all = {"radius"};
  all.insert(all.end(), kinematics.begin(), kinematics.end());
  wire::InitReply dem_reply;
  const Message arrays = dem_arrays(scene, scene_dir, all, dem_reply);
  const std::size_t particles = arrays.array("radius", 1).size();
  for (const std::string exe : {"dem_module", "fluid_module"}) {
    Module module(exe, "mutated_" + exe);
    const wire::ModuleKind kind = exe == "dem_module" ? wire::MODULE_KIND_DEM : wire::MODULE_KIND_FLUID;
    Client owner(module.endpoint);
    Message h = hello(kind);
    ASSERT_TRUE(owner.request(h)->envelope.has_hello_reply());
    Message init = init_for(kind, scene, scene_dir, dem_reply);
    if (kind == wire::MODULE_KIND_FLUID) copy_arrays(arrays, {"radius", "position"}, init);
    const auto init_reply = owner.request(init, 20000ms);
    ASSERT_TRUE(init_reply && init_reply->envelope.has_init_reply()) << error_of(init_reply);
    // The seeds of the mutations.
    std::vector<Message> seeds(7);
    seeds[0] = hello(kind);
    seeds[1] = init_for(kind, scene, scene_dir, dem_reply);
    copy_arrays(arrays, {"radius", "position"}, seeds[1]);
    seeds[2].envelope.mutable_advance()->set_steps(3);
    seeds[2].envelope.mutable_advance()->set_dt_s(1e-7);
    seeds[2].envelope.mutable_advance()->set_split_last(true);
    seeds[3].envelope.mutable_fluid_step()->set_dt_s(1e-7);
    seeds[3].envelope.mutable_fluid_step()->set_report(true);
    auto* probe = seeds[3].envelope.mutable_fluid_step()->add_probes();
    probe->set_name("p1");
    probe->set_x_max_m(0.05);
    probe->set_y_max_m(0.05);
    copy_arrays(arrays, kinematics, seeds[3]);
    seeds[4].envelope.mutable_frame_request()->add_fields("position");
    seeds[5].envelope.mutable_load_state()->mutable_state()->set_module(exe + " x");
    copy_arrays(arrays, {"position"}, seeds[5]);
    seeds[6].envelope.mutable_apply_forces();
    copy_arrays(arrays, {"position"}, seeds[6]);
    seeds[6].envelope.mutable_arrays(0)->set_name("force");
    // The valid step first: the fuzzing starts from a module that has stepped.
    const Message& valid = kind == wire::MODULE_KIND_FLUID ? seeds[3] : seeds[2];
    Message step;
    step.envelope = valid.envelope;
    step.envelope.clear_arrays();
    copy_arrays(valid, kinematics, step);
    const auto stepped = owner.request(step, 20000ms);
    ASSERT_TRUE(stepped && !stepped->envelope.has_error()) << exe << ": " << error_of(stepped);

    if (kind == wire::MODULE_KIND_FLUID) {
      // A wall_segments array shorter than its header claims (once a heap-buffer-overflow in
      // the boundary's faces_segment).
      Message short_walls;
      short_walls.envelope = seeds[3].envelope;
      short_walls.envelope.clear_arrays();
      copy_arrays(seeds[3], kinematics, short_walls);
      for (auto& h : *short_walls.envelope.mutable_arrays()) {
        if (h.name() == "wall_segments") h.set_count(h.count() + 1000);
      }
      EXPECT_NE(error_of(owner.request(short_walls)).find("array 'wall_segments'"),
                std::string::npos);
    }
    std::mt19937_64 rng(fuzz_seed());
    auto uniform = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
    const double rss_start = rss_mib(module.process.pid);
    int answered = 0;
    const int messages = fuzz_messages();
    for (int trial = 0; trial < messages; ++trial) {
      Message& seed = seeds[uniform(seeds.size())];
      wire::Envelope envelope = seed.envelope;
      std::vector<std::string> frames;
      for (int a = 0; a < envelope.arrays_size(); ++a) {
        const auto v = seed.array(envelope.arrays(a).name(), envelope.arrays(a).components());
        frames.emplace_back(reinterpret_cast<const char*>(v.data()), v.size_bytes());
      }
      const int how = static_cast<int>(uniform(6));
      if (how == 0 && envelope.arrays_size() > 0) {  // a count made up
        const std::uint64_t counts[] = {0, 1, particles - 1, particles + 1, 1ull << 61, ~0ull,
                                        3ull << 30};
        envelope.mutable_arrays(static_cast<int>(uniform(envelope.arrays_size())))
            ->set_count(counts[uniform(7)]);
      } else if (how == 1 && !frames.empty()) {  // a frame cut short
        std::string& f = frames[uniform(frames.size())];
        f.resize(uniform(f.size() + 1));
      } else if (how == 2) {  // a frame too many or too few
        if (frames.empty() || uniform(2)) frames.push_back(std::string(uniform(64), 'x'));
        else frames.pop_back();
      } else if (how == 3 && envelope.arrays_size() > 0) {  // components made up
        envelope.mutable_arrays(static_cast<int>(uniform(envelope.arrays_size())))
            ->set_components(static_cast<std::uint32_t>(rng() % 8));
      }
      std::string head = envelope.SerializeAsString();
      if (how >= 4) {  // bytes flipped, the envelope cut or grown
        const std::size_t flips = 1 + uniform(8);
        for (std::size_t k = 0; k < flips && !head.empty(); ++k) head[uniform(head.size())] ^= static_cast<char>(1 + uniform(255));
        if (uniform(3) == 0) head.resize(uniform(head.size() + 16), '\x01');
      }
      // What the mutation made of it must not end the session or run for long: a Shutdown or a
      // long step is put back to a FrameRequest.
      wire::Envelope parsed;
      if (parsed.ParseFromString(head) &&
          (parsed.has_shutdown() ||
           (parsed.has_advance() && !(parsed.advance().steps() <= 100 &&
                                      std::abs(parsed.advance().dt_s()) < 1e-6)) ||
           (parsed.has_fluid_step() && !(std::abs(parsed.fluid_step().dt_s()) < 1e-6)))) {
        head = seeds[4].envelope.SerializeAsString();
        frames.clear();
      }
      frames.insert(frames.begin(), head);
      owner.send_frames(frames);
      const auto reply = owner.receive(10000ms);
      ASSERT_TRUE(reply.has_value()) << exe << ": no reply to mutated message " << trial;
      ++answered;
      ASSERT_TRUE(module.alive()) << exe << " died at message " << trial;
    }
    EXPECT_EQ(answered, messages);
    // Bounded memory: a few tens of MiB for this scene whatever the peer announced.
    EXPECT_LT(rss_mib(module.process.pid) - rss_start, 200.0) << exe;
    // Purely random frame 0s.
    for (int trial = 0; trial < 100; ++trial) {
      std::string bytes(uniform(200), '\0');
      for (char& c : bytes) c = static_cast<char>(rng());
      owner.send_frames({bytes});
      ASSERT_TRUE(owner.receive(10000ms).has_value()) << exe << ": no reply to random bytes";
    }
    shut_down(owner, module);
  }
}

// Random bytes on plain TCP connections, and a ZeroMQ peer announcing a 3 GiB frame: the module
// drops the connection without buffering, and then serves its coupler.
TEST(WireFuzz, RandomBytesAndAHugeFrameOnRawTcpAreDropped) {
  Module dem("dem_module", "raw_tcp");
  const int port = std::stoi(dem.endpoint.substr(dem.endpoint.rfind(':') + 1));
  auto connect_raw = [&] {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    for (int k = 0; k < 100 && connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0; ++k) {
      std::this_thread::sleep_for(20ms);
    }
    timeval tv{5, 0};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    return fd;
  };
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 30; ++trial) {
    const int fd = connect_raw();
    std::string bytes(1 + rng() % 4096, '\0');
    for (char& c : bytes) c = static_cast<char>(rng());
    (void)write(fd, bytes.data(), bytes.size());
    close(fd);
  }
  // ZMTP 3.0 greeting (NULL mechanism), READY as a DEALER, then a frame announcing 3 GiB.
  const int fd = connect_raw();
  std::string greeting(64, '\0');
  greeting[0] = '\xff';
  greeting[9] = '\x7f';
  greeting[10] = 3;
  greeting.replace(12, 4, "NULL");
  const std::string property = std::string("\x0bSocket-Type") + std::string("\0\0\0\x06", 4) + "DEALER";
  const std::string ready_body = std::string("\x05READY") + property;
  std::string ready = std::string("\x04") + static_cast<char>(ready_body.size()) + ready_body;
  std::string huge = "\x02";  // a long frame, no more parts
  const std::uint64_t size = std::uint64_t{3} << 30;
  for (int k = 7; k >= 0; --k) huge += static_cast<char>((size >> (8 * k)) & 0xff);
  const std::string head = greeting + ready + std::string("\x01\x00", 2) + huge;
  ASSERT_EQ(write(fd, head.data(), head.size()), static_cast<ssize_t>(head.size()));
  const std::string chunk(1 << 20, 'z');
  std::size_t sent = 0;
  for (int k = 0; k < 64; ++k) {  // 64 MiB of the 3 GiB: refused long before
    const ssize_t n = send(fd, chunk.data(), chunk.size(), MSG_NOSIGNAL);
    if (n <= 0) break;
    sent += static_cast<std::size_t>(n);
  }
  EXPECT_LT(sent, std::size_t{64} << 20) << "the module kept reading the 3 GiB frame";
  close(fd);
  EXPECT_TRUE(dem.alive());
  EXPECT_LT(rss_mib(dem.process.pid), 100.0);
  Client owner(dem.endpoint);
  Message h = hello(wire::MODULE_KIND_DEM);
  const auto reply = owner.request(h);
  ASSERT_TRUE(reply && reply->envelope.has_hello_reply()) << error_of(reply);
  shut_down(owner, dem);
}

}  // namespace
}  // namespace rockcut::test
