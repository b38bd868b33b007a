// The assembled parts of one run, by reference, for the pieces that act on all of them: the
// checkpoints (checkpoint/checkpoint_writer.hpp) and the start and end reports (session/run_report.hpp).
#pragma once

#include "observers/run_observer.hpp"
#include "run/run_clock.hpp"
#include "run/run_modules.hpp"
#include "run/run_options.hpp"
#include "session/run_recorder.hpp"
#include "run/time_plan.hpp"
#include "schemes/coupling_scheme.hpp"
#include "scene/scene_loader.hpp"

namespace rockcut::coupler {

struct RunParts {
  const RunOptions& options;
  const scene::LoadedScene& loaded;
  const TimePlan& plan;
  RunModules& modules;
  RunClock& clock;
  RunRecorder& recorder;
  const RunObservers& observers;
  const CouplingScheme& scheme;
};

}  // namespace rockcut::coupler
