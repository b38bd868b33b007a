#include "run/run_modules.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <string_view>

#include "process/module_environment.hpp"
#include "run/ipc_directory.hpp"
#include "run/reply_checks.hpp"
#include "wire/init_parts.hpp"
#include "wire/protocol.hpp"
#include "wire/shared_payload.hpp"
#include "wire/state_message.hpp"

namespace rockcut::coupler {

namespace {

namespace fs = std::filesystem;

bool contains(const google::protobuf::RepeatedPtrField<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

// A module is declared stalled when it does not answer within coupling.timeout_s plus the time its
// work may take at a throughput far below anything measured (1e6 particle-steps/s, 20-50 times
// below bench_dem on one core): large or loaded runs are not killed for being slow.
constexpr double kSlowestParticleStepsPerS = 1e6;

// Saving or loading a module's state may take a while at paper scale, and far longer on a
// loaded machine.
constexpr std::chrono::milliseconds kStateTimeout{600000};

}  // namespace

fs::path module_beside_or_on_path(const fs::path& coupler_dir, const std::string& name) {
  const fs::path beside = coupler_dir / name;
  if (::access(beside.c_str(), X_OK) == 0) return beside;
  // An installation may put the modules in another directory of PATH than the coupler (a
  // cluster's software modules, a container's /usr/bin beside a user's own coupler).
  if (const char* path = std::getenv("PATH")) {
    std::string_view dirs(path);
    while (!dirs.empty()) {
      const auto colon = dirs.find(':');
      const std::string_view dir = dirs.substr(0, colon);
      if (!dir.empty()) {
        const fs::path candidate = fs::path(dir) / name;
        if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate)) return candidate;
      }
      if (colon == std::string_view::npos) break;
      dirs.remove_prefix(colon + 1);
    }
  }
  return beside;  // not found: starting it fails with the path the coupler looked at first
}

std::string join_names(const google::protobuf::RepeatedPtrField<std::string>& names) {
  std::string out;
  for (const auto& s : names) out += (out.empty() ? "" : ", ") + s;
  return out;
}

bool RunModule::provides(const std::string& field) const { return contains(init.provides(), field); }

RunModules::RunModules(const RunOptions& options, const scene::LoadedScene& loaded)
    : options_(options), loaded_(loaded) {}

RunModules::~RunModules() {
  // Modules first (they may need the context to say goodbye), then the context, which releases any
  // inproc thread still blocked, then the links' threads are joined.
  if (dem_.link) dem_.link->close();
  if (fluid_ && fluid_->link) fluid_->link->close();
  if (context_) context_->shutdown();
  dem_.link.reset();
  fluid_.reset();
  if (!ipc_dir_.empty()) {
    std::error_code ec;
    fs::remove_all(ipc_dir_, ec);
  }
}

fs::path RunModules::module_executable(const std::string& from_scene, const char* name) const {
  if (from_scene.empty()) return module_beside_or_on_path(options_.module_dir, name);
  fs::path p(from_scene);
  // A relative path in a scene is relative to the scene file, so cases can carry their modules.
  if (p.is_relative()) p = loaded_.path.parent_path() / p;
  return p;
}

void RunModules::start() {
  const rockcut::Scene& scene = loaded_.scene;
  context_.emplace(1);
  if (options_.transport == Transport::ipc) ipc_dir_ = make_private_ipc_directory();
  const auto timeout = std::chrono::milliseconds(
      static_cast<long long>(scene.coupling().timeout_s() * 1000.0));
  auto spec_for = [&](wire::ModuleKind kind, const std::string& exe_from_scene, const char* exe,
                      const std::string& tcp_endpoint) {
    LinkSpec spec;
    spec.kind = kind;
    spec.transport = options_.transport;
    spec.timeout = timeout;
    const std::string short_name = kind == wire::MODULE_KIND_DEM ? "dem" : "fluid";
    switch (options_.transport) {
      case Transport::ipc:
        spec.endpoint = "ipc://" + (ipc_dir_ / (short_name + ".sock")).string();
        spec.executable = module_executable(exe_from_scene, exe);
        break;
      case Transport::inproc: spec.endpoint = "inproc://" + short_name; break;
      case Transport::tcp:
        spec.endpoint = tcp_endpoint;
        spec.curve_keys = options_.curve_keys;
        break;
    }
    return spec;
  };
  // Once per ipc run, before its modules start: modules killed together with an earlier coupler
  // (SIGKILL) could not unlink their shared memory.
  if (options_.transport == Transport::ipc) wire::remove_orphaned_shared_segments();
  // How the modules' idle threads wait (libgomp reads it when a module starts; the coupler's own
  // teams, inproc, keep the default it read before main).
  if (scene.has_fluid()) {
    overlap_ = choose_overlap(scene.coupling().overlap(), options_.transport,
                              scene.dem().threads(), scene.fluid().threads(), usable_cores());
  }
  prepare_module_environment(scene.has_fluid(), overlap_ && !overlap_->overlap);
  dem_.link = std::make_unique<ModuleLink>(
      *context_, spec_for(wire::MODULE_KIND_DEM, scene.dem().executable(), "dem_module",
                          options_.dem_endpoint));
  if (scene.has_fluid()) {
    fluid_.emplace();
    fluid_->link = std::make_unique<ModuleLink>(
        *context_, spec_for(wire::MODULE_KIND_FLUID, scene.fluid().executable(), "fluid_module",
                            options_.fluid_endpoint));
  }
  dem_.hello = dem_.link->handshake();
  if (fluid_) {
    fluid_->hello = fluid_->link->handshake();
    if (!contains(fluid_->hello.models(), scene.fluid().model())) {
      throw wire::ModuleFailure(
          fluid_->label(),
          "the scene asks for fluid.model \"" + scene.fluid().model() + "\", but " +
              fluid_->hello.module_name() + " " + fluid_->hello.module_version() + " offers: " +
              join_names(fluid_->hello.models()),
          /*refused=*/true);
    }
  }
}

void RunModules::init() {
  const rockcut::Scene& scene = loaded_.scene;
  // The scene's directory bounds what a module reads (the DEM's packing file).
  const std::string scene_dir = fs::absolute(loaded_.path).parent_path().lexically_normal().string();
  dem_.request.clear();
  wire::set_dem_part(scene, scene_dir, *dem_.request.envelope.mutable_init());
  dem_.link->request(dem_.request, dem_.reply);
  dem_.init = dem_.reply.envelope.init_reply();
  check_init_reply(dem_.label(), dem_.init, std::nullopt);
  if (!fluid_) return;

  // The fluid gets the static particle data (radius, initial position) once.
  dem_.request.clear();
  dem_.request.envelope.mutable_frame_request()->add_fields(std::string(wire::field::kRadius));
  dem_.request.envelope.mutable_frame_request()->add_fields(std::string(wire::field::kPosition));
  dem_.link->request(dem_.request, dem_.reply);
  fluid_->request.clear();
  // What the fluid needs of the solid comes from the DEM's reply (SolidProperties).
  wire::set_fluid_part(scene, dem_.init, *fluid_->request.envelope.mutable_init());
  fluid_->request.take_arrays(dem_.reply);
  fluid_->link->request(fluid_->request, fluid_->reply);
  fluid_->init = fluid_->reply.envelope.init_reply();
  check_init_reply(fluid_->label(), fluid_->init, dem_.init.particle_count());
  fluid_->busy.read(fluid_->reply.envelope);

  // Subscribe the DEM to exactly the kinematics the fluid model needs: nothing else is sent.
  dem_.request.clear();
  wire::Subscribe* sub = dem_.request.envelope.mutable_subscribe();
  sub->set_external_force_supplies_energy(fluid_->init.supplies_energy());
  for (const std::string& f : fluid_->init.needs()) {
    if (!dem_.provides(f)) {
      throw wire::ModuleFailure(fluid_->label(),
                                "fluid model " + fluid_->init.model() + " needs \"" + f + "\", which " +
                                    dem_.hello.module_name() + " does not provide (it provides " +
                                    join_names(dem_.init.provides()) + ")");
    }
    sub->add_fields(f);
  }
  dem_.busy.read(dem_.reply.envelope);
  for (const std::string& f : dem_.init.needs()) {
    if (!fluid_->provides(f)) {
      throw wire::ModuleFailure(dem_.label(), "needs \"" + f + "\", which fluid model " +
                                                  fluid_->init.model() + " does not provide");
    }
  }
  dem_.link->request(dem_.request, dem_.reply);
}

std::chrono::milliseconds RunModules::allowance(std::uint64_t steps) const {
  const double work_s =
      static_cast<double>(steps) * dem_.init.particle_count() / kSlowestParticleStepsPerS;
  return std::chrono::milliseconds(
      static_cast<long long>((loaded_.scene.coupling().timeout_s() + work_s) * 1000.0));
}

std::vector<Limit> RunModules::dem_limits() const {
  std::vector<Limit> limits;
  for (const auto& l : dem_.init.limits()) {
    limits.push_back(
        {dem_.hello.module_name(), l.name(), l.dt_max_s(), l.detail(), false, "", l.kind()});
  }
  return limits;
}

std::vector<Limit> RunModules::fluid_limits() const {
  std::vector<Limit> limits;
  if (!fluid_) return limits;
  for (const auto& l : fluid_->init.limits()) {
    limits.push_back({fluid_->hello.module_name(), l.name(), l.dt_max_s(), l.detail(),
                      l.lag_only(), l.remedy(), l.kind()});
  }
  return limits;
}

void RunModules::start_loop() {
  dem_.busy.start_loop();
  dem_.request0_s = dem_.link->request_s();
  if (fluid_) {
    fluid_->busy.start_loop();
    fluid_->request0_s = fluid_->link->request_s();
  }
}

void RunModules::save_states(Checkpoint& c) {
  auto take = [](RunModule& module) {
    module.request.clear();
    module.request.envelope.mutable_save_state();
    module.link->set_timeout(kStateTimeout);
    module.link->request(module.request, module.reply);
    if (!module.reply.envelope.has_state()) {
      throw wire::ModuleFailure(module.label(), "answered SaveState without State");
    }
    return wire::take_state(module.reply.envelope.state(), module.reply);
  };
  c.parts["dem"] = take(dem_);
  if (fluid_) c.parts["fluid"] = take(*fluid_);
}

void RunModules::load_states(const Checkpoint& c) {
  auto hand_back = [](RunModule& module, const state::StateArchive& part, const char* what) {
    module.request.clear();
    wire::State* body = module.request.envelope.mutable_load_state()->mutable_state();
    wire::put_state(part, *body, module.request);
    module.link->set_timeout(kStateTimeout);
    module.link->request(module.request, module.reply);
    if (!module.reply.envelope.has_ack()) {
      throw wire::ModuleFailure(module.label(), std::string("answered LoadState (") + what +
                                                    ") without Ack");
    }
  };
  hand_back(dem_, c.parts.at("dem"), "dem");
  if (fluid_) hand_back(*fluid_, c.parts.at("fluid"), "fluid");
}

}  // namespace rockcut::coupler
