// One `coupler run`: assembles a run from its scene (the modules it needs, the time plan, the
// coupling scheme, the recorder, the observers the scene asks for, the checkpoints) and drives
// it to its end, ending cleanly whatever happens (a module failure or stall, a guard, a signal,
// a full disk).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "observers/progress.hpp"
#include "observers/run_observer.hpp"
#include "checkpoint/checkpoint_file.hpp"
#include "output/summary_json.hpp"
#include "checkpoint/checkpoint_writer.hpp"
#include "run/run_clock.hpp"
#include "run/run_modules.hpp"
#include "run/run_options.hpp"
#include "session/run_parts.hpp"
#include "session/run_recorder.hpp"
#include "run/time_plan.hpp"
#include "schemes/coupling_scheme.hpp"
#include "scene/scene_loader.hpp"

namespace rockcut::coupler {

/// Runs the scene and returns the exit code (run_scene.cpp). Messages go to stderr, the result
/// lines to stdout.
int run_scene(const RunOptions& options);

class RunSession : private ExchangeSchedule {
 public:
  /// `resume_from`: the checkpoint a resumed run continues from (already read and verified).
  RunSession(const RunOptions& options, scene::LoadedScene scene,
             std::optional<Checkpoint> resume_from = std::nullopt);
  int run();

 private:
  /// Starts the modules and builds everything the loop needs; throws on a refusal.
  void assemble();
  void open_output();
  void loop();
  RunParts parts() {
    return {options_, loaded_, plan_, modules_, clock_, recorder_, observers_, *scheme_};
  }
  /// The wall time of the loop so far [s].
  double wall_s() const { return progress_ ? progress_->elapsed_s() : 0.0; }

  // ExchangeSchedule, for the coupling scheme.
  bool completes_step_at(std::uint64_t step, double time_s) const override {
    return recorder_.record_due(step, time_s) || (checkpoints_ && checkpoints_->due());
  }
  std::uint64_t steps_to_next_record(std::uint64_t step, double time_s) const override {
    return recorder_.steps_to_next_record(step, time_s);
  }

  RunOptions options_;
  scene::LoadedScene loaded_;
  const rockcut::Scene& scene_;
  std::optional<Checkpoint> resume_from_;

  RunModules modules_;
  TimePlan plan_;
  RunClock clock_;
  RunObservers observers_;
  RunRecorder recorder_;
  std::unique_ptr<CouplingScheme> scheme_;
  std::unique_ptr<RunCheckpoints> checkpoints_;
  Progress* progress_ = nullptr;  // among the observers, from the start of the loop
  std::vector<std::string> startup_report_;
  Summary summary_;
};

}  // namespace rockcut::coupler
