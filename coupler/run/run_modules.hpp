// The modules of a run as the coupler drives them: started (child processes over ipc, threads
// over inproc, or attached over tcp), greeted, initialised and subscribed to exactly the fields
// the other module needs; the messages every exchange reuses; each module's busy time.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <zmq.hpp>

#include "run/checkpoint_values.hpp"
#include "run/module_link.hpp"
#include "run/overlap_choice.hpp"
#include "run/run_options.hpp"
#include "run/time_plan.hpp"
#include "scene/scene_loader.hpp"
#include "wire/message.hpp"

namespace rockcut::coupler {

/// A module's handling time (Envelope.busy_s, after_reply_s) and its step's phases
/// (Envelope.phase_times) at the start of the loop and now.
struct BusyTime {
  double busy0_s = 0.0, busy_s = 0.0, after0_s = 0.0, after_s = 0.0;
  /// (name, cumulative seconds) in the module's step order; empty until a reply carries them.
  std::vector<std::pair<std::string, double>> phases, phases0;
  void read(const wire::Envelope& e) {
    busy_s = e.busy_s();
    after_s = e.after_reply_s();
    if (e.phase_times_size() == 0) return;
    phases.resize(static_cast<std::size_t>(e.phase_times_size()));
    for (int k = 0; k < e.phase_times_size(); ++k) {
      phases[k].first = e.phase_times(k).name();  // same names every time: no allocation
      phases[k].second = e.phase_times(k).seconds();
    }
  }
  void start_loop() {
    busy0_s = busy_s;
    after0_s = after_s;
    phases0 = phases;
  }
  /// Seconds in phase k since the loop started.
  double phase_s(std::size_t k) const {
    return phases[k].second - (k < phases0.size() ? phases0[k].second : 0.0);
  }
};

/// "a, b, c": a list of names (fields, models) for a message.
std::string join_names(const google::protobuf::RepeatedPtrField<std::string>& names);
/// A module program: `name` beside the coupler when it is there (the build tree, an installation's
/// bin/), else the first executable `name` on PATH, else the path beside the coupler (whose start
/// then fails naming it).
std::filesystem::path module_beside_or_on_path(const std::filesystem::path& coupler_dir,
                                               const std::string& name);

struct RunModule {
  std::unique_ptr<ModuleLink> link;
  wire::HelloReply hello;
  wire::InitReply init;
  BusyTime busy;
  double request0_s = 0.0;  ///< link->request_s() at the start of the loop
  // Reused for every message to this module: no allocation of message objects per exchange.
  wire::Message request, reply;
  const std::string& label() const { return link->label(); }
  bool provides(const std::string& field) const;
};

class RunModules {
 public:
  RunModules(const RunOptions& options, const scene::LoadedScene& loaded);
  /// Ends both sessions and removes the private socket directory. Never throws.
  ~RunModules();

  /// Starts the modules the scene needs and shakes hands (protocol version, the fluid model).
  void start();
  /// Init with the scene, the fluid's static particle data, and the subscriptions.
  void init();

  RunModule& dem() { return dem_; }
  const RunModule& dem() const { return dem_; }
  RunModule* fluid() { return fluid_ ? &*fluid_ : nullptr; }
  const RunModule* fluid() const { return fluid_ ? &*fluid_ : nullptr; }
  std::uint64_t particle_count() const { return dem_.init.particle_count(); }
  /// How long the DEM may take to answer an Advance of `steps` steps.
  std::chrono::milliseconds allowance(std::uint64_t steps) const;
  /// The stability limits each module reported at Init (bounding dt and N dt).
  std::vector<Limit> dem_limits() const;
  std::vector<Limit> fluid_limits() const;
  /// A coupled scene's choice of coupling.overlap (made in start(), before the modules' threads
  /// wait in the way it implies); none for a dry scene.
  const std::optional<OverlapChoice>& overlap() const { return overlap_; }
  void start_loop();

  /// Checkpoints: each module's state (SaveState), and back (LoadState).
  void save_states(Checkpoint& c);
  void load_states(const Checkpoint& c);

 private:
  std::filesystem::path module_executable(const std::string& from_scene, const char* name) const;

  const RunOptions& options_;
  const scene::LoadedScene& loaded_;
  std::optional<zmq::context_t> context_;
  std::filesystem::path ipc_dir_;
  RunModule dem_;
  std::optional<RunModule> fluid_;
  std::optional<OverlapChoice> overlap_;
};

}  // namespace rockcut::coupler
