// The clock of a run: the half-step synchronised exchange of DESIGN section 3 for coupled scenes,
// plain multi-step advances for dry ones, and the recording of time series and frames.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "run/reply_checks.hpp"
#include "run/run_session.hpp"
#include "run/signals.hpp"
#include "wire/protocol.hpp"

namespace rockcut::coupler {

void RunSession::loop() {
  forces_held_ = false;  // the clock itself starts at 0, or where a checkpoint left it
  dem_busy_.start_loop();
  fluid_busy_.start_loop();

  // A checkpoint's stop: the first SIGINT/SIGTERM lets the exchange in progress finish.
  set_graceful_stop(checkpoints_);
  if (!resume_from_) {
    if (coupled_) {
      exchange(0, true);  // t = 0: a^0 includes the fluid force
    } else {
      advance_dry(0);
    }
    maybe_record(true);
  }

  const double frame_interval = scene_.output().frame_interval_s();
  bool end_checkpoint_written = false;
  // The end-of-run checkpoint is taken before the advance that the end cuts short and before
  // the last row and frame that only the end asks for: a run continued from it to a later end
  // time exchanges at the same steps and records what an uninterrupted run does.
  auto end_checkpoint = [&] {
    if (checkpoints_ && !end_checkpoint_written) write_checkpoint_now("end of run");
    end_checkpoint_written = true;
  };
  while (step_ < plan_.total_steps && !calibration_->test_over()) {
    const std::uint64_t remaining = plan_.total_steps - step_;
    // The advance the run would make without its end: N steps, or (dry) up to the next output
    // event, with no message per step.
    std::uint64_t regular = plan_.coupling_interval;
    if (!coupled_) {
      regular = next_series_step_ - step_;
      if (frame_interval > 0) {
        const double next_frame_time = next_frame_index_ * frame_interval;
        const double steps_to_frame = std::ceil((next_frame_time - time_s_) / plan_.dt_s - 1e-9);
        regular = std::min<std::uint64_t>(regular, std::max(1.0, steps_to_frame));
      }
      regular = std::clamp<std::uint64_t>(regular, 1, 1u << 30);
    }
    if (remaining < regular) end_checkpoint();
    const auto steps = static_cast<unsigned>(std::min(regular, remaining));
    if (coupled_) {
      exchange(steps, false);
    } else {
      advance_dry(steps);
    }
    maybe_record(false);
    progress_->update(time_s_, step_);
    maybe_checkpoint();
  }
  end_checkpoint();
  set_graceful_stop(false);
  maybe_record(true);
  if (calibration_->test_over()) {
    std::printf("\nthe Brazilian disc split at t = %.6g s: test ended (loading_test.stop_at_split)\n",
                time_s_);
  }
}

namespace {
// A module is declared stalled when it does not answer within coupling.timeout_s plus the time its
// work may take at a throughput far below anything measured (1e6 particle-steps/s, 20-50 times
// below bench_dem on one core): large or loaded runs are not killed for being slow.
constexpr double kSlowestParticleStepsPerS = 1e6;
}  // namespace

std::chrono::milliseconds RunSession::allowance(std::uint64_t steps) const {
  const double work_s =
      static_cast<double>(steps) * dem_.init.particle_count() / kSlowestParticleStepsPerS;
  return std::chrono::milliseconds(
      static_cast<long long>((scene_.coupling().timeout_s() + work_s) * 1000.0));
}

void RunSession::exchange(unsigned steps, bool initial) {
  // 1. DEM: (complete the last step with the held fluid force,) N-1 full steps, then half kick and
  //    drift; answers x^{n+N}, v^{n+N-1/2}.
  request_.clear();
  wire::Advance* advance = request_.envelope.mutable_advance();
  advance->set_steps(steps);
  advance->set_dt_s(plan_.dt_s);
  advance->set_split_last(true);
  if (forces_held_) {
    advance->set_apply_forces_first(true);
    request_.take_arrays(fluid_reply_);
    forces_held_ = false;
  }
  dem_.link->set_timeout(allowance(steps));
  dem_.link->request(request_, reply_);
  if (reply_.envelope.has_step_report()) {
    const wire::StepReport& r = reply_.envelope.step_report();
    check_progress(dem_.link->label(), r.step(), r.time_s(), step_, time_s_, 0, true);
    record_step_report(r);  // a guard tripped on the completed step
  }
  if (!reply_.envelope.has_kinematics()) {
    throw wire::ModuleFailure(dem_.link->label(), "answered Advance without Kinematics");
  }
  const wire::Kinematics& kinematics = reply_.envelope.kinematics();
  const double t = kinematics.time_s();
  const std::uint64_t kinematics_step = kinematics.step();  // reply_ is reused below
  check_progress(dem_.link->label(), kinematics_step, t, step_, time_s_, steps, false);
  dem_busy_.read(reply_.envelope);

  // 2. Fluid: advance the pressure by N dt (nothing at t = 0) and return the forces. The DEM
  //    computes its contact forces meanwhile. Arrays are forwarded, not copied.
  fluid_request_.clear();
  wire::FluidStep* fs = fluid_request_.envelope.mutable_fluid_step();
  fs->set_dt_s(initial ? 0.0 : steps * plan_.dt_s);
  fs->set_time_s(t);
  // The fluid's scalars and pressure nodes only where this exchange is recorded (step 3).
  const bool record = initial || record_due(kinematics.step(), t);
  fs->set_report(record);
  if (record && !nodes_.empty()) {
    const auto tip_x = kinematics.scalars().find("tool_tip_x_m");
    const auto tip_y = kinematics.scalars().find("tool_tip_y_m");
    if (tip_x == kinematics.scalars().end() || tip_y == kinematics.scalars().end()) {
      throw wire::ModuleFailure(dem_.link->label(), "reports no tool tip with its Kinematics");
    }
    place_probes(nodes_, tip_x->second, tip_y->second, *fs);
  }
  bytes_exchanged_ += reply_.payload_bytes();
  bytes_in_shared_memory_ += reply_.shared_payload_bytes();
  fluid_request_.take_arrays(reply_);
  fluid_->link->request(fluid_request_, fluid_reply_);
  if (!fluid_reply_.envelope.has_fluid_result()) {
    throw wire::ModuleFailure(fluid_->link->label(), "answered FluidStep without FluidResult");
  }
  checked_array(fluid_->link->label(), fluid_reply_, std::string(wire::field::kForce), 2,
                dem_.init.particle_count());
  fluid_busy_.read(fluid_reply_.envelope);
  if (fluid_reply_.envelope.fluid_result().has_guard()) {
    throw GuardStop{fluid_->link->label(), fluid_reply_.envelope.fluid_result().guard()};
  }
  bytes_exchanged_ += fluid_reply_.payload_bytes();
  bytes_in_shared_memory_ += fluid_reply_.shared_payload_bytes();
  ++exchanges_;

  // 3. DEM: total force at x^{n+N}, second half kick. When nothing is recorded at this step, the
  //    force rides on the next Advance instead: two round trips per exchange instead of three.
  if (!record) {
    forces_held_ = true;
    step_ = kinematics.step();
    time_s_ = t;
    return;
  }
  request_.clear();
  request_.envelope.mutable_apply_forces();
  request_.take_arrays(fluid_reply_);
  dem_.link->request(request_, reply_);
  if (!reply_.envelope.has_step_report()) {
    throw wire::ModuleFailure(dem_.link->label(), "answered ApplyForces without StepReport");
  }
  check_progress(dem_.link->label(), reply_.envelope.step_report().step(),
                 reply_.envelope.step_report().time_s(), kinematics_step, t, 0, false);
  dem_busy_.read(reply_.envelope);
  scalars_.clear();
  for (const auto& [name, value] : fluid_reply_.envelope.fluid_result().scalars()) {
    scalars_.emplace_back("fluid_" + name, value);
  }
  record_step_report(reply_.envelope.step_report());
}

void RunSession::advance_dry(unsigned steps) {
  request_.clear();
  wire::Advance* advance = request_.envelope.mutable_advance();
  advance->set_steps(steps);
  advance->set_dt_s(plan_.dt_s);
  advance->set_split_last(false);
  dem_.link->set_timeout(allowance(steps));
  dem_.link->request(request_, reply_);
  if (!reply_.envelope.has_step_report()) {
    throw wire::ModuleFailure(dem_.link->label(), "answered Advance without StepReport");
  }
  const wire::StepReport& r = reply_.envelope.step_report();
  check_progress(dem_.link->label(), r.step(), r.time_s(), step_, time_s_, steps, r.has_guard());
  dem_busy_.read(reply_.envelope);
  ++exchanges_;
  scalars_.clear();
  record_step_report(reply_.envelope.step_report());
}

void RunSession::record_step_report(const wire::StepReport& report) {
  time_s_ = report.time_s();
  step_ = report.step();
  // protobuf maps have no stable order: sort so every run writes the same columns.
  for (const auto& [name, value] : report.scalars()) scalars_.emplace_back(name, value);
  std::sort(scalars_.begin(), scalars_.end());
  if (report.has_guard()) throw GuardStop{dem_.link->label(), report.guard()};
}

bool RunSession::series_due(std::uint64_t step) const { return step >= next_series_step_; }

bool RunSession::frame_due(double time_s) const {
  const double interval = scene_.output().frame_interval_s();
  return next_frame_index_ == 0 ||
         (interval > 0 && time_s >= next_frame_index_ * interval - 0.5 * plan_.dt_s);
}

bool RunSession::record_due(std::uint64_t step, double time_s) const {
  // The exchange before a last one shorter than N completes its step too: the end-of-run
  // checkpoint is taken there.
  return step >= plan_.total_steps || plan_.total_steps - step < plan_.coupling_interval ||
         series_due(step) ||
         frame_due(time_s) || checkpoint_due_;
}

void RunSession::maybe_record(bool last) {
  if (series_due(step_) || (last && row_step_ != step_)) {
    row_step_ = step_;
    run_file_->append_timeseries(time_s_, step_, scalars_);
    cutting_->observe(scalars_);
    calibration_->observe(scalars_);
    last = last || calibration_->test_over();  // the Brazilian disc has split: end the test here
    const std::uint64_t every = scene_.output().timeseries_every_steps();
    next_series_step_ = (step_ / every + 1) * every;
  }
  const double interval = scene_.output().frame_interval_s();
  if ((last && frame_step_ != step_) || frame_due(time_s_)) {
    frame_step_ = step_;
    write_frame();
    if (interval > 0) {
      next_frame_index_ = static_cast<std::uint64_t>(std::floor(time_s_ / interval + 0.5)) + 1;
    } else {
      next_frame_index_ = 1;
    }
  }
}

void RunSession::write_breaks(const wire::Message& frame) {
  // One row per bond break in /breaks: time, place and mode (0 tensile, 1 shear).
  const std::string& module = dem_.link->label();
  const auto time = checked_array(module, frame, "break_time_s", 1, std::nullopt);
  const auto position = checked_array(module, frame, "break_position", 2, time.size());
  const auto mode = checked_array(module, frame, "break_mode", 1, time.size());
  for (std::size_t k = 0; k < time.size(); ++k) {
    run_file_->append_record("breaks", time[k], step_,
                             {{"mode", mode[k]}, {"x_m", position[2 * k]}, {"y_m", position[2 * k + 1]}});
  }
}

void RunSession::write_frame() {
  request_.clear();
  for (const std::string& f : dem_frame_fields_) {
    request_.envelope.mutable_frame_request()->add_fields(f);
  }
  if (dem_logs_breaks_) request_.envelope.mutable_frame_request()->add_fields("breaks");
  dem_.link->request(request_, reply_);
  const std::uint64_t particles = dem_.init.particle_count();
  std::vector<FrameField> fields;
  std::uint32_t components = 0;
  for (const std::string& f : dem_frame_fields_) {
    const auto values = frame_array(dem_.link->label(), reply_, f, particles, components);
    fields.push_back({f, static_cast<int>(components), values});
  }
  if (fluid_ && !fluid_frame_fields_.empty()) {
    fluid_request_.clear();
    for (const std::string& f : fluid_frame_fields_) {
      fluid_request_.envelope.mutable_frame_request()->add_fields(f);
    }
    fluid_->link->request(fluid_request_, fluid_reply_);
    for (std::size_t k = 0; k < fluid_frame_fields_.size(); ++k) {
      const std::string& f = fluid_frame_fields_[k];
      const auto values = frame_array(fluid_->link->label(), fluid_reply_, f, particles, components);
      fields.push_back({f, static_cast<int>(components), values});
    }
  }
  const auto position = checked_array(dem_.link->label(), reply_,
                                      std::string(wire::field::kPosition), 2, particles);
  if (initial_position_.empty()) initial_position_.assign(position.begin(), position.end());
  last_position_.assign(position.begin(), position.end());
  for (const FrameField& f : fields) {
    if (std::find(verification_fields_.begin(), verification_fields_.end(), f.name) !=
        verification_fields_.end()) {
      final_fields_[f.name].assign(f.values.begin(), f.values.end());
    }
  }
  // The breaks since the last frame first: the frame's flush then covers them too, so a reader
  // of a run still going finds /breaks complete up to the newest frame (rockcut windows).
  if (dem_logs_breaks_) write_breaks(reply_);
  run_file_->write_frame(time_s_, step_, dem_.init.particle_count(), fields);
}

}  // namespace rockcut::coupler
