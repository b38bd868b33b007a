#include "session/run_recorder.hpp"

#include <algorithm>
#include <cmath>

#include "run/reply_checks.hpp"
#include "checkpoint/resume.hpp"
#include "wire/protocol.hpp"

namespace rockcut::coupler {

namespace {

// The fields every frame carries when the scene names none.
const std::vector<std::string> kDefaultFrameFields = {"position", "velocity", "radius"};

bool has(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

}  // namespace

RunRecorder::RunRecorder(const rockcut::Scene& scene, const TimePlan& plan, RunModules& modules,
                         const RunObservers& observers)
    : scene_(scene), plan_(plan), modules_(modules), observers_(observers) {}

void RunRecorder::choose_frame_fields(const std::vector<std::string>& extra,
                                      const std::string& extra_for) {
  const RunModule& dem = modules_.dem();
  const RunModule* fluid = modules_.fluid();
  dem_logs_breaks_ = dem.provides("breaks") && scene_.dem().has_bonds();
  std::vector<std::string> wanted(scene_.output().frame_fields().begin(),
                                  scene_.output().frame_fields().end());
  if (wanted.empty()) wanted = kDefaultFrameFields;
  if (!has(wanted, "position")) wanted.insert(wanted.begin(), "position");  // the XDMF geometry
  for (const std::string& f : wanted) {
    if (dem.provides(f)) {
      dem_frame_fields_.push_back(f);
    } else if (fluid && fluid->provides(f)) {
      fluid_frame_fields_.push_back(f);
    } else {
      throw PlanError("output.frame_fields: \"" + f + "\" is provided by no module of this scene (" +
                      dem.hello.module_name() + ": " + join_names(dem.init.provides()) +
                      (fluid ? "; " + fluid->init.model() + ": " + join_names(fluid->init.provides())
                             : std::string("; no fluid")) +
                      ")");
    }
  }
  // Fields compared at the end are written in every frame (the last one is kept).
  for (const std::string& f : extra) {
    if (has(dem_frame_fields_, f) || has(fluid_frame_fields_, f)) continue;
    if (fluid && fluid->provides(f)) {
      fluid_frame_fields_.push_back(f);
    } else {
      throw PlanError(extra_for + " needs the field \"" + f +
                      "\", which no module of this scene provides");
    }
  }
}

void RunRecorder::open(const std::filesystem::path& out_dir, const std::string& scene_text,
                       const std::map<std::string, std::string>& attributes,
                       const RunFileExtent* resume_extent) {
  if (resume_extent) {
    // Cut back to what the checkpoint recorded: rows and frames after it are written again.
    std::vector<std::string> field_order = dem_frame_fields_;
    field_order.insert(field_order.end(), fluid_frame_fields_.begin(), fluid_frame_fields_.end());
    file_ = RunFile::resume(out_dir, *resume_extent, field_order, attributes);
  } else {
    file_ = std::make_unique<RunFile>(out_dir, scene_text, attributes);
  }
}

bool RunRecorder::frame_due(double time_s) const {
  const double interval = scene_.output().frame_interval_s();
  return next_frame_index_ == 0 ||
         (interval > 0 && time_s >= next_frame_index_ * interval - 0.5 * plan_.dt_s);
}

bool RunRecorder::record_due(std::uint64_t step, double time_s) const {
  // The exchange before a last one shorter than N completes its step too: the end-of-run
  // checkpoint is taken there.
  return step >= plan_.total_steps || plan_.total_steps - step < plan_.coupling_interval ||
         series_due(step) || frame_due(time_s);
}

std::uint64_t RunRecorder::steps_to_next_record(std::uint64_t step, double time_s) const {
  std::uint64_t steps = next_series_step_ - step;
  const double interval = scene_.output().frame_interval_s();
  if (interval > 0) {
    const double next_frame_time = next_frame_index_ * interval;
    const double steps_to_frame = std::ceil((next_frame_time - time_s) / plan_.dt_s - 1e-9);
    steps = std::min<std::uint64_t>(steps, std::max(1.0, steps_to_frame));
  }
  return steps;
}

void RunRecorder::write_row(const RunClock& clock) {
  file_->append_timeseries(clock.time_s, clock.step, clock.scalars);
}

void RunRecorder::record(const RunClock& clock, bool last) {
  if (series_due(clock.step) || (last && row_step_ != clock.step)) {
    row_step_ = clock.step;
    write_row(clock);
    observers_.each([&](RunObserver& o) { o.row(clock); });
    last = last || observers_.ends_run();  // e.g. the Brazilian disc has split: end the test here
    const std::uint64_t every = scene_.output().timeseries_every_steps();
    next_series_step_ = (clock.step / every + 1) * every;
  }
  const double interval = scene_.output().frame_interval_s();
  if ((last && frame_step_ != clock.step) || frame_due(clock.time_s)) {
    frame_step_ = clock.step;
    write_frame(clock);
    if (interval > 0) {
      next_frame_index_ =
          static_cast<std::uint64_t>(std::floor(clock.time_s / interval + 0.5)) + 1;
    } else {
      next_frame_index_ = 1;
    }
  }
}

void RunRecorder::write_breaks(const RunClock& clock, const wire::Message& frame) {
  // One row per bond break in /breaks: time, place and mode (0 tensile, 1 shear).
  const std::string& module = modules_.dem().label();
  const auto time = checked_array(module, frame, "break_time_s", 1, std::nullopt);
  const auto position = checked_array(module, frame, "break_position", 2, time.size());
  const auto mode = checked_array(module, frame, "break_mode", 1, time.size());
  for (std::size_t k = 0; k < time.size(); ++k) {
    file_->append_record("breaks", time[k], clock.step,
                         {{"mode", mode[k]}, {"x_m", position[2 * k]}, {"y_m", position[2 * k + 1]}});
  }
}

void RunRecorder::write_frame(const RunClock& clock) {
  RunModule& dem = modules_.dem();
  RunModule* fluid = modules_.fluid();
  dem.request.clear();
  for (const std::string& f : dem_frame_fields_) {
    dem.request.envelope.mutable_frame_request()->add_fields(f);
  }
  if (dem_logs_breaks_) dem.request.envelope.mutable_frame_request()->add_fields("breaks");
  dem.link->request(dem.request, dem.reply);
  const std::uint64_t particles = modules_.particle_count();
  std::vector<FrameField> fields;
  std::uint32_t components = 0;
  for (const std::string& f : dem_frame_fields_) {
    const auto values = frame_array(dem.label(), dem.reply, f, particles, components);
    fields.push_back({f, static_cast<int>(components), values});
  }
  if (fluid && !fluid_frame_fields_.empty()) {
    fluid->request.clear();
    for (const std::string& f : fluid_frame_fields_) {
      fluid->request.envelope.mutable_frame_request()->add_fields(f);
    }
    fluid->link->request(fluid->request, fluid->reply);
    for (const std::string& f : fluid_frame_fields_) {
      const auto values = frame_array(fluid->label(), fluid->reply, f, particles, components);
      fields.push_back({f, static_cast<int>(components), values});
    }
  }
  checked_array(dem.label(), dem.reply, std::string(wire::field::kPosition), 2, particles);
  observers_.each([&](RunObserver& o) { o.frame(clock, fields); });
  // The breaks since the last frame first: the frame's flush then covers them too, so a reader
  // of a run still going finds /breaks complete up to the newest frame (rockcut windows).
  if (dem_logs_breaks_) write_breaks(clock, dem.reply);
  file_->write_frame(clock.time_s, clock.step, particles, fields);
}

void RunRecorder::save_state(state::StateArchive& a) const {
  a.put("record_schedule", std::vector<double>{static_cast<double>(next_series_step_),
                                               static_cast<double>(next_frame_index_)});
  save_extent(a, file_->extent());
}

void RunRecorder::load_state(const state::StateArchive& a) {
  const auto schedule = a.values("record_schedule", 2);
  next_series_step_ = static_cast<std::uint64_t>(schedule[0]);
  next_frame_index_ = static_cast<std::uint64_t>(schedule[1]);
}

}  // namespace rockcut::coupler
