// A module's session against a client that is not its coupler, or not yet one: bad Inits, an Init
// without the module's part, a second client, CURVE keys (the module keeps serving its own
// coupler, which ends the session cleanly), and a coupled run over CURVE.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "integration/h5_read.hpp"
#include "integration/process_helpers.hpp"
#include "integration/summary_values.hpp"
#include "integration/wire_peer.hpp"
#include "wire/curve_keys.hpp"
#include "wire/init_parts.hpp"
#include "wire/message.hpp"
#include "wire/protocol.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using wire::Message;

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
    Module dem("dem_module", "bad_init_" + c.name, {"--read-under", scene_dir.string()});
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

// Over tcp the scene directory in Init comes from the peer: a module reads only under its own
// --read-under directory (default: its working directory), so an Init naming "/" as the scene's
// directory cannot make it read a file elsewhere (a 0600 file of the module's user included).
TEST(WireFuzz, APeerCannotWidenWhatTheModuleReads) {
  const fs::path elsewhere = fresh_dir("read_root_elsewhere");
  std::ofstream(elsewhere / "packing.txt") << "0.001 0.001 0.0005\n";  // a valid packing
  fs::permissions(elsewhere / "packing.txt", fs::perms::owner_read | fs::perms::owner_write);
  for (const std::string& scene_dir : {std::string("/"), elsewhere.string()}) {
    Module dem("dem_module", "read_root");  // working directory: its own fresh folder
    Client client(dem.endpoint);
    Message h = hello(wire::MODULE_KIND_DEM);
    ASSERT_TRUE(client.request(h)->envelope.has_hello_reply());
    rockcut::Scene scene = tiny_scene();
    scene.mutable_dem()->mutable_packing_file()->set_path((elsewhere / "packing.txt").string());
    Message init = init_of(scene, scene_dir);
    const std::string error = error_of(client.request(init, 20000ms));
    EXPECT_NE(error.find("outside the directory this module reads under"), std::string::npos)
        << scene_dir << ": " << error;
    EXPECT_NE(error.find("--read-under"), std::string::npos) << error;
    shut_down(client, dem);
  }
  // Told to read there, the same module takes the same Init.
  Module dem("dem_module", "read_root_granted", {"--read-under", elsewhere.string()});
  Client client(dem.endpoint);
  Message h = hello(wire::MODULE_KIND_DEM);
  ASSERT_TRUE(client.request(h)->envelope.has_hello_reply());
  rockcut::Scene scene = tiny_scene();
  scene.mutable_dem()->mutable_packing_file()->set_path("packing.txt");
  Message init = init_of(scene, elsewhere.string());
  const auto reply = client.request(init, 20000ms);
  ASSERT_TRUE(reply.has_value());
  EXPECT_TRUE(reply->envelope.has_init_reply()) << error_of(reply);
  shut_down(client, dem);
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

// Keys that do not match: ZeroMQ drops the failed CURVE handshake silently, so the coupler can only
// time out; it says that this is what mismatched keys look like instead of "stopped answering".
TEST(WireFuzz, MismatchedCurveKeysAreNamedAsTheLikelyCause) {
  const fs::path dir = fresh_dir("curve_mismatch");
  wire::make_curve_keys(dir / "module_keys", {"coupler", "dem_module", "fluid_module"});
  wire::make_curve_keys(dir / "coupler_keys", {"coupler", "dem_module", "fluid_module"});
  const std::string dem = "tcp://127.0.0.1:" + std::to_string(free_tcp_port());
  const std::string fluid = "tcp://127.0.0.1:" + std::to_string(free_tcp_port());
  const std::string module_keys = (dir / "module_keys").string();
  const Spawned sd = spawn({bin("dem_module"), "--bind", dem, "--curve-keys", module_keys}, dir, "dem");
  const Spawned sf =
      spawn({bin("fluid_module"), "--bind", fluid, "--curve-keys", module_keys}, dir, "fluid");
  KillOnExit kd{sd.pid}, kf{sf.pid};
  std::string err;
  const int code = run({bin("coupler"), "run", source("cases/verification/pressure_gradient.pbtxt"),
                        "--out", (dir / "out").string(), "--transport", "tcp", "--dem-endpoint",
                        dem, "--fluid-endpoint", fluid, "--curve-keys",
                        (dir / "coupler_keys").string(), "--set", "coupling.timeout_s=1"},
                       dir, "coupler", nullptr, &err);
  EXPECT_EQ(code, 3) << err;
  EXPECT_NE(err.find("keys that do not match"), std::string::npos) << err;
  EXPECT_EQ(err.find("stopped answering"), std::string::npos) << err;
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
