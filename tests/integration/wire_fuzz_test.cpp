// A module on a loopback tcp port against a hostile or careless peer: malformed, random and
// mutated wire messages, random bytes on a raw TCP connection, a frame announcing 3 GiB, bad
// Inits, a second client, CURVE keys. Each case asserts that the module is not killed by a
// signal, answers within a timeout (an Error or a dropped connection), keeps its memory bounded
// and keeps serving its own coupler, which ends the session cleanly (exit 0).
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>

#include <zmq.hpp>

#include "integration/h5_read.hpp"
#include "integration/process_helpers.hpp"
#include "integration/summary_values.hpp"
#include "scene/scene_loader.hpp"
#include "wire/curve_keys.hpp"
#include "wire/init_parts.hpp"
#include "wire/message.hpp"
#include "wire/protocol.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using wire::Message;

// Resident memory of `pid` [MiB] (VmRSS).
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

// A module started by hand with --bind on a free loopback port.
struct Module {
  fs::path dir;
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
  bool alive() const { return !wait_exit(process.pid, 0ms).has_value(); }
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
  bool send(Message& message) {
    zmq::message_t empty;
    if (!socket.send(empty, zmq::send_flags::sndmore)) return false;
    message.send(socket);
    return true;
  }
  // The reply, or nothing within `timeout`.
  std::optional<Message> receive(std::chrono::milliseconds timeout = 5000ms) {
    zmq::pollitem_t item{socket.handle(), 0, ZMQ_POLLIN, 0};
    if (zmq::poll(&item, 1, timeout) <= 0) return std::nullopt;
    zmq::message_t empty;
    (void)socket.recv(empty);
    zmq::message_t head;
    (void)socket.recv(head);
    Message reply;
    reply.receive_body(socket, head);
    return reply;
  }
  std::optional<Message> request(Message& message, std::chrono::milliseconds timeout = 5000ms) {
    if (!send(message)) return std::nullopt;
    return receive(timeout);
  }
};

Message hello(wire::ModuleKind kind, unsigned version = wire::kProtocolVersion) {
  Message m;
  m.envelope.mutable_hello()->set_protocol_version(version);
  m.envelope.mutable_hello()->set_expected_kind(kind);
  return m;
}

// A small dry scene: a 30 x 30 lattice falling freely.
rockcut::Scene tiny_scene() {
  return scene::load_scene(source("cases/verification/free_fall.pbtxt"), {}).scene;
}

// The DEM's Init of `scene`.
Message init_of(const rockcut::Scene& scene, const std::string& scene_dir = "") {
  Message m;
  wire::set_dem_part(scene, scene_dir, *m.envelope.mutable_init());
  return m;
}

// The fluid's Init of `scene`, with the solid properties of the DEM's reply `dem`.
Message fluid_init_of(const rockcut::Scene& scene, const wire::InitReply& dem) {
  Message m;
  wire::set_fluid_part(scene, dem, *m.envelope.mutable_init());
  return m;
}

// The Init of a module of `kind`.
Message init_for(wire::ModuleKind kind, const rockcut::Scene& scene, const std::string& scene_dir,
                 const wire::InitReply& dem) {
  return kind == wire::MODULE_KIND_FLUID ? fluid_init_of(scene, dem) : init_of(scene, scene_dir);
}

std::string error_of(const std::optional<Message>& reply) {
  if (!reply) return "<no reply>";
  return reply->envelope.has_error() ? reply->envelope.error().message() : "<not an Error>";
}

// Ends the owner's session and expects a clean exit.
void shut_down(Client& owner, Module& module) {
  Message m;
  m.envelope.mutable_shutdown();
  const auto reply = owner.request(m);
  ASSERT_TRUE(reply && reply->envelope.has_ack());
  EXPECT_EQ(wait_exit(module.process.pid, 5000ms), 0);
}

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

// Each bad Init on a module of its own (a module takes one Init): a clear Error, bounded memory.
TEST(WireFuzz, BadInitsAreRefusedWithAClearError) {
  const fs::path scene_dir = fresh_dir("bad_init_scene");
  const fs::path outside = fresh_dir("bad_init_outside") / "secret.txt";
  std::ofstream(outside) << "0.001 0.001 TOP-SECRET-CONTENT\n";
  std::ofstream(scene_dir / "bad.txt") << "0.001 0.001 NOT-A-NUMBER\n";
  struct Case {
    std::string name, expected;
    std::function<void(rockcut::Scene&)> edit;
  };
  const std::vector<Case> cases = {
      {"radius_0", "radius_m = 0", [](rockcut::Scene& s) { s.mutable_dem()->mutable_lattice()->set_radius_m(0); }},
      {"radius_nan", "not a finite number", [](rockcut::Scene& s) { s.mutable_dem()->mutable_lattice()->set_radius_m(NAN); }},
      {"spacing_0", "spacing_m = 0", [](rockcut::Scene& s) { s.mutable_dem()->mutable_lattice()->set_spacing_m(0); }},
      {"lattice_1e10", "at most 2000000 particles", [](rockcut::Scene& s) {
         s.mutable_dem()->mutable_lattice()->set_nx(100000);
         s.mutable_dem()->mutable_lattice()->set_ny(100000);
       }},
      {"threads_huge", "threads = 4000000000", [](rockcut::Scene& s) { s.mutable_dem()->set_threads(4000000000u); }},
      {"packing_dev_zero", "outside the scene's directory", [](rockcut::Scene& s) {
         s.mutable_dem()->mutable_packing_file()->set_path("/dev/zero");
       }},
      {"packing_escape", "outside the scene's directory", [&](rockcut::Scene& s) {
         s.mutable_dem()->mutable_packing_file()->set_path(
             "../" + outside.parent_path().filename().string() + "/secret.txt");
       }},
      {"packing_etc", "outside the scene's directory", [](rockcut::Scene& s) {
         s.mutable_dem()->mutable_packing_file()->set_path("../../../../../../../../etc/hostname");
       }},
      {"packing_not_a_number", ":1: not a number", [](rockcut::Scene& s) {
         s.mutable_dem()->mutable_packing_file()->set_path("bad.txt");
       }},
      {"packing_missing_outside", "outside the scene's directory", [](rockcut::Scene& s) {
         s.mutable_dem()->mutable_packing_file()->set_path("/nonexistent/file.txt");
       }},
  };
  for (const Case& c : cases) {
    Module dem("dem_module", "bad_init_" + c.name);
    Client client(dem.endpoint);
    Message h = hello(wire::MODULE_KIND_DEM);
    ASSERT_TRUE(client.request(h)->envelope.has_hello_reply());
    rockcut::Scene scene = tiny_scene();
    c.edit(scene);
    Message init = init_of(scene, scene_dir.string());
    const std::string error = error_of(client.request(init, 20000ms));
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.name << ": " << error;
    EXPECT_EQ(error.find("SECRET"), std::string::npos) << c.name << " echoes the file: " << error;
    EXPECT_EQ(error.find("NOT-A-NUMBER"), std::string::npos) << c.name << " echoes the file";
    EXPECT_LT(rss_mib(dem.process.pid), 200.0) << c.name;
    shut_down(client, dem);
  }
}

// Each module takes only its own part of the scene: an Init with the other module's part, or with
// none, is refused with an error that names what is missing and where it belongs. The DEM's part is
// checked with the scene's rules and field paths (the particle budget included, above).
TEST(WireFuzz, AModuleRefusesAnInitWithoutItsPart) {
  struct Case {
    std::string exe, expected, not_expected;
    std::function<void(wire::Init&)> fill;
  };
  const std::vector<Case> cases = {
      {"dem_module", "Init carries no DEM part (Init.dem", "", [](wire::Init&) {}},
      {"dem_module", "it carries the fluid's part (Init.fluid), which is for fluid_module", "",
       [](wire::Init& init) { init.mutable_fluid()->mutable_fluid()->set_model("explicit"); }},
      {"dem_module", "the DEM part of the scene sent in Init is not valid: missing required field "
                     "\"dem\"", "",
       [](wire::Init& init) { init.mutable_dem()->set_scene_dir("/"); }},
      {"dem_module", "dem.density_kg_m3 = -1 is out of range", "",
       [](wire::Init& init) {
         wire::set_dem_part(tiny_scene(), "", init);
         init.mutable_dem()->mutable_dem()->set_density_kg_m3(-1);
       }},
      {"fluid_module", "Init carries no fluid part (Init.fluid", "DEM's part",
       [](wire::Init&) {}},
      {"fluid_module", "it carries the DEM's part (Init.dem), which is for dem_module", "",
       [](wire::Init& init) { wire::set_dem_part(tiny_scene(), "", init); }},
  };
  for (const Case& c : cases) {
    Module module(c.exe, "part_" + c.exe);
    Client client(module.endpoint);
    Message h = hello(c.exe == "dem_module" ? wire::MODULE_KIND_DEM : wire::MODULE_KIND_FLUID);
    ASSERT_TRUE(client.request(h)->envelope.has_hello_reply());
    Message init;
    c.fill(*init.envelope.mutable_init());
    const std::string error = error_of(client.request(init, 20000ms));
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.exe << ": " << error;
    if (!c.not_expected.empty()) {
      EXPECT_EQ(error.find(c.not_expected), std::string::npos) << c.exe << ": " << error;
    }
    shut_down(client, module);
  }
}

// A module serves the first client whose Hello it accepted; every other is refused, and cannot
// advance, read or end the owner's session.
TEST(WireFuzz, ASecondClientIsRefused) {
  Module dem("dem_module", "second_client");
  Client owner(dem.endpoint), intruder(dem.endpoint);
  Message h = hello(wire::MODULE_KIND_DEM);
  ASSERT_TRUE(owner.request(h)->envelope.has_hello_reply());
  Message init = init_of(tiny_scene());
  ASSERT_TRUE(owner.request(init)->envelope.has_init_reply());
  Message intruder_hello = hello(wire::MODULE_KIND_DEM);
  EXPECT_NE(error_of(intruder.request(intruder_hello)).find("another coupler"), std::string::npos);
  Message frame;
  frame.envelope.mutable_frame_request()->add_fields("position");
  EXPECT_NE(error_of(intruder.request(frame)).find("another coupler"), std::string::npos);
  Message advance;
  advance.envelope.mutable_advance()->set_steps(5);
  advance.envelope.mutable_advance()->set_dt_s(2e-5);
  EXPECT_NE(error_of(intruder.request(advance)).find("another coupler"), std::string::npos);
  Message stop;
  stop.envelope.mutable_shutdown();
  EXPECT_NE(error_of(intruder.request(stop)).find("another coupler"), std::string::npos);
  EXPECT_TRUE(dem.alive());
  const auto report = owner.request(advance);
  ASSERT_TRUE(report && report->envelope.has_step_report());
  EXPECT_EQ(report->envelope.step_report().step(), 5u);  // the intruder's Advance did nothing
  shut_down(owner, dem);
}

// CURVE: the coupler's key opens the session, any other key (or none) gets no session at all.
TEST(WireFuzz, CurveAcceptsOnlyTheCouplersKey) {
  const fs::path keys = fresh_dir("curve") / "keys";
  ASSERT_EQ(run({bin("coupler"), "keygen", keys.string()}, keys.parent_path(), "keygen"), 0);
  EXPECT_EQ(fs::status(keys / "coupler.secret").permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_EQ(fs::status(keys).permissions() & fs::perms::all, fs::perms::owner_all);
  const fs::path other = fresh_dir("curve_other") / "keys";
  wire::make_curve_keys(other, {"coupler"});
  Module dem("dem_module", "curve_module", {"--curve-keys", keys.string()});
  const std::string server_key = wire::read_public_key(keys, "dem_module");
  const wire::CurveKeyPair right = wire::read_key_pair(keys, "coupler");
  const wire::CurveKeyPair wrong = wire::read_key_pair(other, "coupler");
  Client plain(dem.endpoint), stranger(dem.endpoint, &wrong, server_key);
  Message h = hello(wire::MODULE_KIND_DEM);
  EXPECT_FALSE(plain.request(h, 1500ms).has_value());
  EXPECT_FALSE(stranger.request(h, 1500ms).has_value());
  EXPECT_TRUE(dem.alive());
  Client owner(dem.endpoint, &right, server_key);
  const auto reply = owner.request(h);
  ASSERT_TRUE(reply && reply->envelope.has_hello_reply()) << error_of(reply);
  shut_down(owner, dem);
}

// A whole coupled run over CURVE gives the bits of plain tcp (and of ipc, by the transports test).
TEST(WireFuzz, CurveRunIsBitIdenticalToPlainTcp) {
  const fs::path keys = fresh_dir("curve_run") / "keys";
  wire::make_curve_keys(keys, {"coupler", "dem_module", "fluid_module"});
  auto run_tcp = [&](bool curve) {
    const fs::path dir = fresh_dir(curve ? "curve_run_curve" : "curve_run_plain");
    std::vector<std::string> key_args;
    if (curve) key_args = {"--curve-keys", keys.string()};
    const std::string dem = "tcp://127.0.0.1:" + std::to_string(free_tcp_port());
    const std::string fluid = "tcp://127.0.0.1:" + std::to_string(free_tcp_port());
    std::vector<std::string> d = {bin("dem_module"), "--bind", dem}, f = {bin("fluid_module"), "--bind", fluid};
    d.insert(d.end(), key_args.begin(), key_args.end());
    f.insert(f.end(), key_args.begin(), key_args.end());
    const Spawned sd = spawn(d, dir, "dem"), sf = spawn(f, dir, "fluid");
    KillOnExit kd{sd.pid}, kf{sf.pid};
    std::vector<std::string> argv = {bin("coupler"), "run", source("cases/verification/pressure_gradient.pbtxt"),
                                     "--out", (dir / "out").string(), "--transport", "tcp",
                                     "--dem-endpoint", dem, "--fluid-endpoint", fluid};
    argv.insert(argv.end(), key_args.begin(), key_args.end());
    std::string err;
    EXPECT_EQ(run(argv, dir, "coupler", nullptr, &err), 0) << err;
    EXPECT_EQ(wait_exit(sd.pid, 5000ms), 0);
    EXPECT_EQ(wait_exit(sf.pid, 5000ms), 0);
    return dir / "out";
  };
  const fs::path plain = run_tcp(false), curve = run_tcp(true);
  H5Reader a(plain / "run.h5"), b(curve / "run.h5");
  ASSERT_FALSE(a.members("/frames").empty());
  for (const std::string& frame : a.members("/frames")) {
    const std::string p = "/frames/" + frame + "/position";
    EXPECT_TRUE(bit_identical(a.doubles(p), b.doubles(p))) << p;
  }
  EXPECT_TRUE(bit_identical(a.doubles("/timeseries/time_s"), b.doubles("/timeseries/time_s")));
}

}  // namespace
}  // namespace rockcut::test
