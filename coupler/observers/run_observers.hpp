// Which observers a run has: what its scene asks for, and nothing else. A dry scene gets no
// pressure nodes, a scene without a tool no cutting summary, one without a loading test no
// calibration fit, one without a verification block no check.
#pragma once

#include <filesystem>

#include "observers/run_observer.hpp"
#include "observers/verification.hpp"
#include "run/time_plan.hpp"

namespace rockcut::coupler {

/// What the started modules said that decides the observers.
struct ObserverInputs {
  std::string dem_label;              ///< blamed for kinematics without a tool tip
  bool fluid_has_pressure = false;    ///< the fluid model provides a pressure (pressure nodes)
  std::vector<Limit> dem_limits, fluid_limits;  ///< for the expected error of the settings
  std::filesystem::path program_dir;  ///< where the expected-error table is found from
};

/// Registers the observers `scene` asks for, in the order they report. Throws PlanError for a
/// verification the scene cannot be checked against.
void register_observers(const rockcut::Scene& scene, const TimePlan& plan,
                                      const ObserverInputs& inputs, RunObservers& observers);

}  // namespace rockcut::coupler
