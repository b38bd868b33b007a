#include "session/run_session.hpp"

#include <cstdio>
#include <iostream>

#include "observers/run_observers.hpp"
#include "run/ipc_directory.hpp"
#include "checkpoint/resume.hpp"
#include "session/run_report.hpp"
#include "run/signals.hpp"
#include "wire/protocol.hpp"

namespace rockcut::coupler {

namespace fs = std::filesystem;

RunSession::RunSession(const RunOptions& options, scene::LoadedScene scene,
                       std::optional<Checkpoint> resume_from)
    : options_(options), loaded_(std::move(scene)), scene_(loaded_.scene),
      resume_from_(std::move(resume_from)), modules_(options_, loaded_),
      recorder_(scene_, plan_, modules_, observers_) {
  if (options_.out_dir.empty()) options_.out_dir = fs::path("out") / loaded_.path.stem();
}

void RunSession::assemble() {
  modules_.start();
  modules_.init();
  const std::vector<Limit> fluid_limits = applicable_fluid_limits(scene_, modules_.fluid_limits());
  plan_ = plan_time(scene_, modules_.dem_limits(), fluid_limits, scene_.has_fluid());
  if (const auto& overlap = modules_.overlap()) {
    plan_.forces_before_reply = !overlap->overlap;
    plan_.report.push_back(overlap->report);
  }
  const RunModule* fluid = modules_.fluid();
  const ObserverInputs inputs{modules_.dem().label(),
                              fluid && fluid->provides(std::string(wire::field::kPressure)),
                              modules_.dem_limits(), fluid_limits, options_.module_dir};
  register_observers(scene_, plan_, inputs, observers_);
  // A verification check's fields go into every frame.
  const VerificationCheck* verification = observers_.find<VerificationCheck>();
  recorder_.choose_frame_fields(
      verification ? verification->fields() : std::vector<std::string>{},
      "verification." + scene_.verification().analytical());
  scheme_ = make_coupling_scheme(scene_, plan_, modules_, observers_);
  checkpoints_ = std::make_unique<RunCheckpoints>(parts());
  if (resume_from_) checkpoints_->restore(*resume_from_);  // before run.h5 is touched
}

void RunSession::open_output() {
  fs::create_directories(options_.out_dir);
  if (resume_from_) {
    // Cut back to what the checkpoint recorded: rows and frames after it are written again.
    const RunFileExtent extent = load_extent(resume_from_->parts.at("coupler"));
    recorder_.open(options_.out_dir, "", run_attributes(parts()), &extent);
  } else {
    // A fresh run: what an earlier run left here must not pass for this one's (its summary, its
    // checkpoints, which a resume would otherwise continue).
    std::error_code ec;
    fs::remove(options_.out_dir / "summary.json", ec);
    fs::remove_all(options_.out_dir / "checkpoints", ec);
    recorder_.open(options_.out_dir, loaded_.effective_text(), run_attributes(parts()), nullptr);
  }
  start_summary(parts(), summary_);
  observers_.each([&](RunObserver& o) { o.start(summary_, startup_report_); });
}

int RunSession::run() {
  try {
    assemble();
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
  } catch (const EnvironmentError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::runtime_error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitModuleFailed;
  }
  try {
    open_output();
  } catch (const std::exception& e) {
    std::cerr << "error: cannot write output in " << options_.out_dir << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  print_startup(parts(), startup_report_);
  const auto where = [&] {
    char at[128];
    std::snprintf(at, sizeof at, "at t = %.6g s (step %llu)", clock_.time_s,
                  static_cast<unsigned long long>(clock_.step));
    return std::string(at);
  };
  try {
    loop();
  } catch (const wire::ModuleFailure& e) {
    std::fprintf(stderr, "\nerror: %s %s; run stopped, output so far in %s\n", e.what(),
                 where().c_str(), options_.out_dir.c_str());
    return finish_run(parts(), summary_, wall_s(), kExitModuleFailed, "failed", e.what());
  } catch (const GuardStop& stop) {
    return stop_on_guard(parts(), summary_, wall_s(), stop);
  } catch (const wire::Interrupted&) {
    const int sig = stop_signal();
    std::fprintf(stderr, "\nstopped by signal %d %s; output so far in %s\n", sig, where().c_str(),
                 options_.out_dir.c_str());
    return finish_run(parts(), summary_, wall_s(), 128 + sig, "interrupted",
                      "signal " + std::to_string(sig));
  } catch (const std::exception& e) {
    // Writing the output failed (a full disk, ulimit -f): the run stops, what was flushed stays.
    std::fprintf(stderr, "\nerror: writing the output failed %s: %s\n", where().c_str(), e.what());
    return finish_run(parts(), summary_, wall_s(), kExitOutputFailed, "failed",
                      std::string("writing the output: ") + e.what());
  }
  return finish_run(parts(), summary_, wall_s(), kExitOk, "completed", "");
}

void RunSession::loop() {
  auto progress = std::make_unique<Progress>(scene_.time().end_time_s(), plan_.total_steps, stderr,
                                             clock_.step);
  progress_ = progress.get();
  observers_.add_first(std::move(progress));
  modules_.start_loop();
  // A checkpoint's stop: the first SIGINT/SIGTERM lets the exchange in progress finish.
  set_graceful_stop(checkpoints_->enabled());
  if (!resume_from_) {
    scheme_->initialise(clock_);  // t = 0: a^0 includes the external force
    recorder_.record(clock_, true);
  }
  // The end-of-run checkpoint is taken before the exchange that the end cuts short and before
  // the last row and frame that only the end asks for: a run continued from it to a later end
  // time exchanges at the same steps and records what an uninterrupted run does.
  bool end_checkpoint_written = false;
  auto end_checkpoint = [&] {
    if (checkpoints_->enabled() && !end_checkpoint_written) checkpoints_->write_now("end of run", wall_s());
    end_checkpoint_written = true;
  };
  while (!scheme_->done(clock_) && !observers_.ends_run()) {
    const std::uint64_t remaining = plan_.total_steps - clock_.step;
    const std::uint64_t regular = scheme_->regular_steps(clock_, *this);
    if (remaining < regular) end_checkpoint();
    scheme_->advance(clock_, static_cast<unsigned>(std::min(regular, remaining)), *this);
    recorder_.record(clock_, false);
    observers_.each([&](RunObserver& o) { o.exchanged(clock_); });
    checkpoints_->after_exchange(wall_s());
  }
  end_checkpoint();
  set_graceful_stop(false);
  recorder_.record(clock_, true);
  if (observers_.ends_run()) std::printf("\n%s\n", observers_.end_reason(clock_).c_str());
}

}  // namespace rockcut::coupler
