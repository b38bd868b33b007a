// The expected error of a cutting run's settings, from the work-precision study of docs/accuracy.md
// (scripts/accuracy): printed at start-up where the study covers the scene.
#pragma once

#include <optional>
#include <string>

#include "rockcut/scene.pb.h"
#include "run/time_plan.hpp"

namespace rockcut::coupler {

/// The settings the study varies, as the scene and the time plan fix them.
struct CutSettings {
  double dt_safety = 0.0;       ///< dt / the DEM's stability limit
  double fluid_step_ratio = 0.0;  ///< N dt / the pore_fluid_stiffness limit (N = 1: 0)
  double h_per_diameter = 0.0;  ///< smoothing length / mean disc diameter
  double size_scale = 0.0;      ///< mean radius / that of saturated_reduced (1.2 mm)
};

/// One line for the start-up report: the expected relative error of the mean horizontal force for
/// each setting, and their root sum square; or why the study does not cover the scene. Nothing for scenes that are not saturated cuts of a specimen.
std::optional<std::string> expected_error_line(const rockcut::Scene& scene, const TimePlan& plan,
                                               double dem_limit_s, double fluid_stiffness_limit_s);

/// The same from settings (for tests): empty when a setting is outside the study's range.
std::optional<double> expected_force_error(const CutSettings& settings, std::string* detail);

}  // namespace rockcut::coupler
