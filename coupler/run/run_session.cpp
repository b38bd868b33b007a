#include "run/run_session.hpp"

#include <stdlib.h>

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "run/energy_budget.hpp"
#include "run/expected_error.hpp"
#include "run/ipc_directory.hpp"
#include "run/out_dir_lock.hpp"
#include "run/reply_checks.hpp"
#include "run/signals.hpp"
#include "run/verification.hpp"
#include "wire/protocol.hpp"
#include "wire/shared_payload.hpp"

namespace rockcut::coupler {

namespace {

namespace fs = std::filesystem;

bool contains(const google::protobuf::RepeatedPtrField<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

std::string join(const google::protobuf::RepeatedPtrField<std::string>& list) {
  std::string out;
  for (const auto& s : list) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// The fields every frame carries when the scene names none.
const std::vector<std::string> kDefaultFrameFields = {"position", "velocity", "radius"};

}  // namespace

// A packing file named in the scene is relative to the scene file; the DEM gets it absolute.
void make_paths_absolute(scene::LoadedScene& loaded) {
  if (!loaded.scene.dem().has_packing_file()) return;
  const fs::path p(loaded.scene.dem().packing_file().path());
  if (p.is_relative()) {
    loaded.scene.mutable_dem()->mutable_packing_file()->set_path(
        fs::absolute(loaded.path.parent_path() / p).lexically_normal().string());
  }
}

int run_scene(const RunOptions& options_in) {
  RunOptions options = options_in;
  std::optional<Checkpoint> checkpoint;
  scene::LoadedScene loaded;
  std::optional<OutDirLock> lock;
  try {
    if (!options.resume) loaded = scene::load_scene(options.scene_path, options.overrides);
    if (options.out_dir.empty()) options.out_dir = fs::path("out") / loaded.path.stem();
    try {
      lock.emplace(options.out_dir);  // before anything in it is read or changed
    } catch (const std::runtime_error& e) {
      std::cerr << "error: " << e.what() << "\n";
      return kExitBadInput;
    }
    if (options.resume || options.resume_if_possible) {
      if (const int code = choose_checkpoint(options, loaded, checkpoint); code != kExitOk) {
        return code;
      }
    }
    // A fresh run would replace an earlier run's output at its first step: only when asked to.
    if (!checkpoint && !options.overwrite && fs::exists(options.out_dir / "run.h5")) {
      std::cerr << "error: " << options.out_dir.string()
                << " holds the output of an earlier run (run.h5): give --overwrite to replace it, "
                   "use coupler resume to continue it, or choose another --out\n";
      return kExitBadInput;
    }
  } catch (const scene::SceneError& e) {
    std::cerr << e.what() << (std::string(e.what()).ends_with('\n') ? "" : "\n");
    return kExitBadInput;
  }
  install_stop_signal_handlers();
  RunSession session(options, std::move(loaded), std::move(checkpoint));
  return session.run();
}

RunSession::RunSession(const RunOptions& options, scene::LoadedScene scene,
                       std::optional<Checkpoint> resume_from)
    : options_(options), loaded_(std::move(scene)), scene_(loaded_.scene),
      resume_from_(std::move(resume_from)) {
  coupled_ = scene_.has_fluid();
  if (options_.out_dir.empty()) options_.out_dir = fs::path("out") / loaded_.path.stem();
  peclet_ = peclet_number(scene_);
  calibration_ = std::make_unique<CalibrationSummary>(scene_);
  make_paths_absolute(loaded_);
  checkpoints_ = !options_.no_checkpoints;
  next_checkpoint_time_s_ = scene_.output().checkpoint_interval_s();
}

RunSession::~RunSession() {
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

fs::path RunSession::module_executable(const std::string& from_scene, const char* name) const {
  if (from_scene.empty()) return options_.module_dir / name;
  fs::path p(from_scene);
  // A relative path in a scene is relative to the scene file, so cases can carry their modules.
  if (p.is_relative()) p = loaded_.path.parent_path() / p;
  return p;
}

void RunSession::start_modules() {
  context_.emplace(1);
  if (options_.transport == Transport::ipc) ipc_dir_ = make_private_ipc_directory();
  const auto timeout = std::chrono::milliseconds(
      static_cast<long long>(scene_.coupling().timeout_s() * 1000.0));
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
  dem_.link = std::make_unique<ModuleLink>(
      *context_, spec_for(wire::MODULE_KIND_DEM, scene_.dem().executable(), "dem_module",
                          options_.dem_endpoint));
  if (coupled_) {
    fluid_.emplace();
    fluid_->link = std::make_unique<ModuleLink>(
        *context_, spec_for(wire::MODULE_KIND_FLUID, scene_.fluid().executable(), "fluid_module",
                            options_.fluid_endpoint));
  }
  dem_.hello = dem_.link->handshake();
  if (fluid_) {
    fluid_->hello = fluid_->link->handshake();
    if (!contains(fluid_->hello.models(), scene_.fluid().model())) {
      throw wire::ModuleFailure(
          fluid_->link->label(),
          "the scene asks for fluid.model \"" + scene_.fluid().model() + "\", but " +
              fluid_->hello.module_name() + " " + fluid_->hello.module_version() + " offers: " +
              join(fluid_->hello.models()),
          /*refused=*/true);
    }
  }
}

void RunSession::init_modules() {
  request_.clear();
  // The scene's directory bounds what a module reads (the DEM's packing file).
  const std::string scene_dir = fs::absolute(loaded_.path).parent_path().lexically_normal().string();
  *request_.envelope.mutable_init()->mutable_scene() = scene_;
  request_.envelope.mutable_init()->set_scene_dir(scene_dir);
  dem_.link->request(request_, reply_);
  dem_.init = reply_.envelope.init_reply();
  check_init_reply(dem_.link->label(), dem_.init, std::nullopt);
  if (!fluid_) return;

  // The fluid gets the static particle data (radius, initial position) once.
  request_.clear();
  request_.envelope.mutable_frame_request()->add_fields(std::string(wire::field::kRadius));
  request_.envelope.mutable_frame_request()->add_fields(std::string(wire::field::kPosition));
  dem_.link->request(request_, reply_);
  fluid_request_.clear();
  *fluid_request_.envelope.mutable_init()->mutable_scene() = scene_;
  fluid_request_.envelope.mutable_init()->set_scene_dir(scene_dir);
  fluid_request_.take_arrays(reply_);
  fluid_->link->request(fluid_request_, fluid_reply_);
  fluid_->init = fluid_reply_.envelope.init_reply();
  check_init_reply(fluid_->link->label(), fluid_->init, dem_.init.particle_count());
  fluid_busy_.read(fluid_reply_.envelope);

  // Subscribe the DEM to exactly the kinematics the fluid model needs: nothing else is sent.
  request_.clear();
  wire::Subscribe* sub = request_.envelope.mutable_subscribe();
  sub->set_external_force_supplies_energy(fluid_->init.supplies_energy());
  for (const std::string& f : fluid_->init.needs()) {
    if (!contains(dem_.init.provides(), f)) {
      throw wire::ModuleFailure(fluid_->link->label(),
                                "fluid model " + fluid_->init.model() + " needs \"" + f + "\", which " +
                                    dem_.hello.module_name() + " does not provide (it provides " +
                                    join(dem_.init.provides()) + ")");
    }
    sub->add_fields(f);
  }
  dem_busy_.read(reply_.envelope);
  for (const std::string& f : dem_.init.needs()) {
    if (!contains(fluid_->init.provides(), f)) {
      throw wire::ModuleFailure(dem_.link->label(), "needs \"" + f + "\", which fluid model " +
                                                        fluid_->init.model() +
                                                        " does not provide");
    }
  }
  dem_.link->request(request_, reply_);
}

void RunSession::choose_pressure_nodes() {
  // Pressure nodes need a fluid model with a pressure; others (prescribed_gradient, a third
  // party's) run without them.
  if (fluid_ && contains(fluid_->init.provides(), std::string(wire::field::kPressure))) {
    nodes_ = pressure_nodes(scene_);
  }
  std::vector<std::string> node_names;
  for (const PressureNodeBox& n : nodes_) node_names.push_back(n.name);
  cutting_ = std::make_unique<CuttingSummary>(scene_, std::move(node_names));
}

void RunSession::check_frame_fields() {
  dem_logs_breaks_ = contains(dem_.init.provides(), "breaks") && scene_.dem().has_bonds();
  std::vector<std::string> wanted(scene_.output().frame_fields().begin(),
                                  scene_.output().frame_fields().end());
  if (wanted.empty()) wanted = kDefaultFrameFields;
  if (std::find(wanted.begin(), wanted.end(), "position") == wanted.end()) {
    wanted.insert(wanted.begin(), "position");  // the XDMF geometry
  }
  for (const std::string& f : wanted) {
    if (contains(dem_.init.provides(), f)) {
      dem_frame_fields_.push_back(f);
    } else if (fluid_ && contains(fluid_->init.provides(), f)) {
      fluid_frame_fields_.push_back(f);
    } else {
      throw PlanError("output.frame_fields: \"" + f + "\" is provided by no module of this scene (" +
                      dem_.hello.module_name() + ": " + join(dem_.init.provides()) +
                      (fluid_ ? "; " + fluid_->init.model() + ": " + join(fluid_->init.provides())
                              : std::string("; no fluid")) +
                      ")");
    }
  }
  // Fields the verification compares at the end are written in every frame (the last one is kept).
  if (!scene_.has_verification()) return;
  try {
    verification_fields_ = verification_fields(scene_);
  } catch (const std::invalid_argument& e) {
    throw PlanError(e.what());
  }
  for (const std::string& f : verification_fields_) {
    auto has = [&](const std::vector<std::string>& v) {
      return std::find(v.begin(), v.end(), f) != v.end();
    };
    if (has(dem_frame_fields_) || has(fluid_frame_fields_)) continue;
    if (fluid_ && contains(fluid_->init.provides(), f)) {
      fluid_frame_fields_.push_back(f);
    } else {
      throw PlanError("verification." + scene_.verification().analytical() + " needs the field \"" +
                      f + "\", which no module of this scene provides");
    }
  }
}

void RunSession::open_output() {
  fs::create_directories(options_.out_dir);
  std::map<std::string, std::string> attributes = {
      {"rockcut_version", ROCKCUT_VERSION},
      {"protocol_version", std::to_string(wire::kProtocolVersion)},
      {"scene_path", loaded_.path.string()},
      {"transport", transport_name(options_.transport)},
      {"dem_module", dem_.hello.module_name() + " " + dem_.hello.module_version()},
      {"status", "running"}};
  if (fluid_) {
    attributes["fluid_module"] = fluid_->hello.module_name() + " " + fluid_->hello.module_version();
    attributes["fluid_model"] = fluid_->init.model();
  }
  if (resume_from_) {
    // Cut back to what the checkpoint recorded: rows and frames after it are written again.
    const RunFileExtent extent = load_extent(resume_from_->parts.at("coupler"));
    std::vector<std::string> field_order = dem_frame_fields_;
    field_order.insert(field_order.end(), fluid_frame_fields_.begin(), fluid_frame_fields_.end());
    run_file_ = RunFile::resume(options_.out_dir, extent, field_order, attributes);
  } else {
    // A fresh run: what an earlier run left here must not pass for this one's (its summary, its
    // checkpoints, which a resume would otherwise continue).
    std::error_code ec;
    fs::remove(options_.out_dir / "summary.json", ec);
    fs::remove_all(options_.out_dir / "checkpoints", ec);
    run_file_ = std::make_unique<RunFile>(options_.out_dir, loaded_.effective_text(), attributes);
  }
  summary_.set("scene", loaded_.path.string());
  summary_.set("title", scene_.title());
  summary_.set("transport", std::string(transport_name(options_.transport)));
  summary_.set("particles", static_cast<std::int64_t>(dem_.init.particle_count()));
  summary_.set("dt_s", plan_.dt_s);
  summary_.set("coupling_interval", static_cast<std::int64_t>(plan_.coupling_interval));
  summary_.set("fluid_model", fluid_ ? fluid_->init.model() : std::string("none"));
  if (fluid_) {
    summary_.set("water_depth_m", scene_.water_depth_m());
    summary_.set("hydrostatic_pressure_pa", hydrostatic_pressure_pa(scene_));
  }
  if (peclet_) {
    summary_.set("peclet_number", peclet_->value);
    summary_.set("regime", peclet_->regime);
  }
}

void RunSession::print_startup() const {
  std::fprintf(stderr, "scene      %s%s\n", loaded_.path.c_str(),
               scene_.title().empty() ? "" : (" (" + scene_.title() + ")").c_str());
  std::fprintf(stderr, "transport  %s\n", transport_name(options_.transport));
  std::fprintf(stderr, "dem        %s %s, %llu particles\n", dem_.link->label().c_str(),
               dem_.hello.module_version().c_str(),
               static_cast<unsigned long long>(dem_.init.particle_count()));
  if (fluid_) {
    std::fprintf(stderr, "fluid      %s %s, model %s, needs [%s]\n", fluid_->link->label().c_str(),
                 fluid_->hello.module_version().c_str(), fluid_->init.model().c_str(),
                 join(fluid_->init.needs()).c_str());
  } else {
    std::fprintf(stderr, "fluid      none (dry scene: no fluid process)\n");
  }
  for (const std::string& note : dem_.init.notes()) std::fprintf(stderr, "dem        %s\n", note.c_str());
  for (const std::string& line : plan_.report) std::fprintf(stderr, "%s\n", line.c_str());
  if (peclet_) {
    std::fprintf(stderr,
                 "peclet     Pe = v_c t_c / (4 D) = %.3g (D = M kappa / mu = %.3g m^2/s): %s "
                 "regime (drained < 0.001 < transient < 10 < undrained)\n",
                 peclet_->value, peclet_->diffusivity_m2_s, peclet_->regime.c_str());
  }
  if (fluid_) {
    std::fprintf(stderr, "water      depth %.6g m, p_hydro %.6g Pa%s\n", scene_.water_depth_m(),
                 hydrostatic_pressure_pa(scene_),
                 nodes_.empty() ? "" : (", " + std::to_string(nodes_.size()) +
                                        " pressure nodes moving with the tool").c_str());
  }
  if (accuracy_line_) std::fprintf(stderr, "%s\n", accuracy_line_->c_str());
  std::fprintf(stderr, "output     %s\n", options_.out_dir.c_str());
}

int RunSession::run() {
  try {
    start_modules();
    init_modules();
    choose_pressure_nodes();
    check_frame_fields();
    std::vector<Limit> dem_limits, fluid_limits;
    for (const auto& l : dem_.init.limits()) {
      dem_limits.push_back({dem_.hello.module_name(), l.name(), l.dt_max_s(), l.detail(), false, ""});
    }
    if (fluid_) {
      for (const auto& l : fluid_->init.limits()) {
        fluid_limits.push_back(
            {fluid_->hello.module_name(), l.name(), l.dt_max_s(), l.detail(), l.lag_only(),
             l.remedy()});
      }
    }
    plan_ = plan_time(scene_, dem_limits, fluid_limits, coupled_);
    double dem_limit_s = 0.0, stiffness_limit_s = 0.0;
    for (const Limit& l : dem_limits) {
      if (dem_limit_s == 0.0 || l.dt_max_s < dem_limit_s) dem_limit_s = l.dt_max_s;
    }
    for (const Limit& l : fluid_limits) {
      if (l.name == "pore_fluid_stiffness") stiffness_limit_s = l.dt_max_s;
    }
    accuracy_line_ =
        expected_error_line(scene_, plan_, dem_limit_s, stiffness_limit_s, options_.module_dir);
    if (resume_from_) {
      check_resume_scene();
      restore_from_checkpoint();  // before run.h5 is touched: a refusal leaves it whole
    }
  } catch (const PlanError& e) {
    std::cerr << loaded_.path.string() << ": refused: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const wire::ModuleFailure& e) {
    // A module that answers Init with an error has refused the scene: bad input, nothing ran.
    std::cerr << (e.refused() ? loaded_.path.string() + ": refused by " : std::string("error: "))
              << e.what() << "\n";
    return e.refused() ? kExitBadInput : kExitModuleFailed;
  } catch (const wire::Interrupted&) {
    std::cerr << "interrupted during start-up\n";
    return 128 + stop_signal();
  } catch (const std::runtime_error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitModuleFailed;
  }

  print_startup();
  try {
    open_output();
  } catch (const std::exception& e) {
    std::cerr << "error: cannot write output in " << options_.out_dir << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  progress_ = std::make_unique<Progress>(scene_.time().end_time_s(), plan_.total_steps, stderr,
                                         step_);
  try {
    loop();
  } catch (const wire::ModuleFailure& e) {
    std::fprintf(stderr, "\nerror: %s at t = %.6g s (step %llu); run stopped, output so far in %s\n",
                 e.what(), time_s_, static_cast<unsigned long long>(step_),
                 options_.out_dir.c_str());
    return finish(kExitModuleFailed, "failed", e.what());
  } catch (const GuardStop& stop) {
    return stop_on_guard(stop);
  } catch (const wire::Interrupted&) {
    const int sig = stop_signal();
    std::fprintf(stderr, "\nstopped by signal %d at t = %.6g s (step %llu); output so far in %s\n",
                 sig, time_s_, static_cast<unsigned long long>(step_), options_.out_dir.c_str());
    return finish(128 + sig, "interrupted", "signal " + std::to_string(sig));
  } catch (const std::exception& e) {
    // Writing the output failed (a full disk, ulimit -f): the run stops, what was flushed stays.
    std::fprintf(stderr, "\nerror: writing the output failed at t = %.6g s (step %llu): %s\n",
                 time_s_, static_cast<unsigned long long>(step_), e.what());
    return finish(kExitOutputFailed, "failed", std::string("writing the output: ") + e.what());
  }
  progress_->finish(time_s_, step_);

  int code = kExitOk;
  if (scene_.has_verification()) {
    FinalState state{time_s_, initial_position_, last_position_, {}};
    for (const auto& [name, values] : final_fields_) state.fields.emplace(name, values);
    const VerificationResult v = verify(scene_, state);
    summary_.set("verification", v.analytical);
    summary_.set("error_max_rel", v.error_max_rel);
    summary_.set("error_l2_rel", v.error_l2_rel);
    summary_.set("error_tolerance_rel", v.tolerance_rel);
    summary_.set("verification_passed", v.passed);
    std::printf("verification %s: error_max_rel %.3e, error_l2_rel %.3e (tolerance %.1e): %s\n",
                v.analytical.c_str(), v.error_max_rel, v.error_l2_rel, v.tolerance_rel,
                v.passed ? "passed" : "FAILED");
    if (!v.passed) code = kExitVerificationFailed;
  }
  return finish(code, "completed", "");
}

int RunSession::stop_on_guard(const GuardStop& stop) {
  const wire::GuardTrip& g = stop.trip;
  std::fprintf(stderr,
               "\nerror: %s stopped the run (guard %s): %s\n"
               "       at t = %.6g s (step %llu), particle %lld at (%.6g, %.6g) m; output so far, "
               "with the last frame, in %s\n",
               stop.module.c_str(), g.guard().c_str(), g.message().c_str(), g.time_s(),
               static_cast<unsigned long long>(step_), static_cast<long long>(g.particle()),
               g.x_m(), g.y_m(), options_.out_dir.c_str());
  // The state that tripped the guard, for a look in ParaView; the modules still answer frames.
  try {
    run_file_->append_timeseries(time_s_, step_, scalars_);
    write_frame();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "       (the last frame could not be written: %s)\n", e.what());
  }
  summary_.set("failure_guard", g.guard());
  summary_.set("failure_module", stop.module);
  summary_.set("failure_time_s", g.time_s());
  summary_.set("failure_particle", static_cast<std::int64_t>(g.particle()));
  summary_.set("failure_x_m", g.x_m());
  summary_.set("failure_y_m", g.y_m());
  summary_.set("failure_value", g.value());
  summary_.set("failure_limit", g.limit());
  return finish(kExitUnstable, "failed", g.guard() + " guard: " + g.message());
}

int RunSession::finish(int code, const std::string& status, const std::string& reason) {
  const double wall = wall_before_s_ + (progress_ ? progress_->elapsed_s() : 0.0);
  summary_.set("status", status);
  cutting_->write(summary_);
  calibration_->write(summary_);
  if (!reason.empty()) summary_.set("error", reason);
  summary_.set("time_s", time_s_);
  summary_.set("steps", static_cast<std::int64_t>(step_));
  summary_.set("exchanges", static_cast<std::int64_t>(exchanges_));
  summary_.set("bytes_exchanged", static_cast<std::int64_t>(bytes_exchanged_));
  summary_.set("bytes_in_shared_memory", static_cast<std::int64_t>(bytes_in_shared_memory_));
  summary_.set("wall_time_s", wall);
  summary_.set("particle_steps_per_s",
               wall > 0 ? static_cast<double>(dem_.init.particle_count()) * step_ / wall : 0.0);
  // Where the wall time went: each module's own handling time during the loop, and the part of it
  // after its replies, which overlaps the other module's work (the DEM's contact forces during
  // the fluid step). The rest of the wall is the transport, the coupler's output and waiting.
  summary_.set("dem_busy_s", dem_busy_.busy_s - dem_busy_.busy0_s);
  summary_.set("dem_after_reply_s", dem_busy_.after_s - dem_busy_.after0_s);
  // The energy budget of DESIGN section 5 at the end (the DEM reports it with every step report).
  const auto imbalance = std::find_if(scalars_.begin(), scalars_.end(), [](const auto& s) {
    return s.first == "energy_imbalance_rel";
  });
  if (imbalance != scalars_.end()) summary_.set("energy_imbalance_rel", imbalance->second);
  const std::optional<EnergyBudget> budget = energy_budget(scalars_);
  if (budget) {
    for (const auto& [key, value] : budget->terms()) summary_.set(key, value);
  }
  if (fluid_) {
    summary_.set("fluid_busy_s", fluid_busy_.busy_s - fluid_busy_.busy0_s);
    summary_.set("fluid_after_reply_s", fluid_busy_.after_s - fluid_busy_.after0_s);
  }
  // run.h5 and summary.json each on their own: a run.h5 that cannot be closed (a full disk)
  // still gets its summary.json, which then says so.
  try {
    if (run_file_) {
      run_file_->set_attribute("status", reason.empty() ? status : status + ": " + reason);
      run_file_->set_attribute("wall_time_s", std::to_string(wall));
      run_file_->close();
    }
  } catch (const std::exception& e) {
    std::cerr << "error: closing " << (options_.out_dir / "run.h5").string() << ": " << e.what()
              << "\n";
    if (code == kExitOk) code = kExitOutputFailed;
    summary_.set("status", std::string("failed"));
    if (reason.empty()) summary_.set("error", std::string("closing run.h5: ") + e.what());
  }
  try {
    summary_.write(options_.out_dir / "summary.json");
  } catch (const std::exception& e) {
    std::cerr << "error: writing " << (options_.out_dir / "summary.json").string() << ": "
              << e.what() << "\n";
    if (code == kExitOk) code = kExitOutputFailed;
  }
  if (imbalance != scalars_.end()) {
    std::fprintf(stderr, "energy     imbalance %.3g of the energy throughput (given = kinetic + "
                 "strain + damping + friction + broken bonds)\n", imbalance->second);
  }
  if (budget) {
    std::fprintf(stderr, "energy     %s\n",
                 describe(*budget, fluid_ ? "pore fluid" : "external force").c_str());
  }
  if (status == "completed") {
    std::printf("done: %llu steps of %llu particles in %.3f s wall (%.3g particle-steps/s); "
                "output in %s\n",
                static_cast<unsigned long long>(step_),
                static_cast<unsigned long long>(dem_.init.particle_count()), wall,
                wall > 0 ? static_cast<double>(dem_.init.particle_count()) * step_ / wall : 0.0,
                options_.out_dir.c_str());
  }
  return code;
}

}  // namespace rockcut::coupler
