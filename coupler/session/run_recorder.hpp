// What a run writes as it goes: a time-series row every output.timeseries_every_steps, a frame of
// per-particle fields every output.frame_interval_s (with the bond breaks since the last one), into
// run.h5 (output/run_file.hpp). It tells the coupling scheme where a step must be completed, and
// hands every row and frame to the observers.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "observers/run_observer.hpp"
#include "output/run_file.hpp"
#include "run/run_clock.hpp"
#include "run/run_modules.hpp"
#include "run/time_plan.hpp"
#include "wire/state_archive.hpp"

namespace rockcut::coupler {

class RunRecorder {
 public:
  RunRecorder(const rockcut::Scene& scene, const TimePlan& plan, RunModules& modules,
              const RunObservers& observers);
  /// Decides which module writes each frame field (output.frame_fields, positions always, and
  /// `extra`: what a verification compares). Throws PlanError for a field no module provides.
  void choose_frame_fields(const std::vector<std::string>& extra, const std::string& extra_for);
  /// A fresh run.h5, or (`resume_extent`) the earlier one cut back to what a checkpoint recorded.
  void open(const std::filesystem::path& out_dir, const std::string& scene_text,
            const std::map<std::string, std::string>& attributes,
            const RunFileExtent* resume_extent);
  RunFile& file() { return *file_; }
  bool is_open() const { return file_ != nullptr; }

  /// Whether the step ending at (step, time_s) is recorded, or is the last.
  bool record_due(std::uint64_t step, double time_s) const;
  std::uint64_t steps_to_next_record(std::uint64_t step, double time_s) const;
  /// Writes the row and the frame that are due (`last`: the end of the run, which has both).
  void record(const RunClock& clock, bool last);
  void write_row(const RunClock& clock);
  void write_frame(const RunClock& clock);

  /// Checkpoints: when the next row and frame are due.
  void save_state(state::StateArchive& a) const;
  void load_state(const state::StateArchive& a);

 private:
  bool series_due(std::uint64_t step) const { return step >= next_series_step_; }
  bool frame_due(double time_s) const;
  void write_breaks(const RunClock& clock, const wire::Message& frame);

  const rockcut::Scene& scene_;
  const TimePlan& plan_;
  RunModules& modules_;
  const RunObservers& observers_;
  std::unique_ptr<RunFile> file_;
  std::vector<std::string> dem_frame_fields_, fluid_frame_fields_;
  bool dem_logs_breaks_ = false;  // the DEM hands out its bond breaks with every frame
  std::uint64_t next_series_step_ = 0;
  std::uint64_t next_frame_index_ = 0;
  // The steps of the last row and frame written: the end of a run adds one only where none is.
  std::uint64_t row_step_ = static_cast<std::uint64_t>(-1);
  std::uint64_t frame_step_ = static_cast<std::uint64_t>(-1);
};

}  // namespace rockcut::coupler
