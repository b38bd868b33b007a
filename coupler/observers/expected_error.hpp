// The expected error of a cutting run's settings, from the work-precision study of docs/accuracy.md
// (rockcut accuracy): printed at start-up where the study covers the scene. The study's numbers
// are data (coupler/data/expected_error.csv), read at run time from beside the program.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "observers/run_observer.hpp"
#include "rockcut/scene.pb.h"
#include "run/time_plan.hpp"

namespace rockcut::coupler {

/// The settings the study varies, as the scene and the time plan fix them.
struct CutSettings {
  double dt_safety = 0.0;       ///< dt / the DEM's stability limit
  double fluid_step_ratio = 0.0;  ///< N dt / the applicable pore-fluid stiffness limit (N = 1: 0)
  double h_per_diameter = 0.0;  ///< smoothing length / mean disc diameter
  double size_scale = 0.0;      ///< mean radius / that of saturated_reduced (1.2 mm)
};

/// One setting of a ladder and the relative error of the study's horizontal force there.
struct LadderPoint {
  double value = 0.0;
  double force_error = 0.0;
};

/// The study's four ladders (the columns of CutSettings), each coarsest first, finest last, for
/// one damping model, and the force whose error they give: "mean" (force_horizontal_mean_n_per_m,
/// the study under local damping) or "peak" (force_horizontal_peak_n_per_m, under dashpots, where
/// the mean is mostly the zeros between chips: docs/model.md, "Damping").
struct ErrorModel {
  std::string force = "mean";
  std::vector<LadderPoint> dt_safety, fluid_step_ratio, h_per_diameter, size_scale;
};

/// Where the study's table lies for a program in `program_dir`: ../share/rockcut/expected_error.csv
/// (the build tree and an installation alike).
std::filesystem::path error_model_path(const std::filesystem::path& program_dir);

/// Reads the study's rows for `damping` (a dem.damping.model) from its table (CSV: '#' comment
/// lines, a header naming `ladder`, `value` and `force_error`, and optionally `damping` (a row
/// without it is "local") and `force` ("mean" or "peak", the same on every row of one damping;
/// "mean" without it), and optionally `fluid_force` (coupling.fluid_force, "held" without it;
/// only fluid_step_ratio rows may be "extrapolated"), one row per setting). The fluid_step_ratio
/// ladder is that of `fluid_force`; with "extrapolated" and no such rows it is empty (not covered).
/// Empty when the table has no row for `damping`; then `studied`, if given, gets the damping
/// models it has. Throws std::runtime_error "FILE:LINE: problem" on a file that cannot be read, a
/// bad number, an unknown ladder, force or fluid_force, a ladder with fewer than two settings or
/// settings out of order.
std::optional<ErrorModel> read_error_model(const std::filesystem::path& csv,
                                           const std::string& damping = "local",
                                           std::vector<std::string>* studied = nullptr,
                                           const std::string& fluid_force = "held");

/// One line for the start-up report: the expected relative error of the study's horizontal force
/// (mean or peak, by the scene's damping) for each setting, and their root sum square; or why the
/// study does not cover the scene, or why its table could not be read. Nothing for scenes that are
/// not saturated cuts of a specimen.
std::optional<std::string> expected_error_line(const rockcut::Scene& scene, const TimePlan& plan,
                                               double dem_limit_s, double fluid_stiffness_limit_s,
                                               const std::filesystem::path& program_dir);

/// The same from settings: empty when a setting is coarser than the study's coarsest; a setting
/// finer than the finest gets the finest's error (the study cannot resolve it).
std::optional<double> expected_force_error(const ErrorModel& model, const CutSettings& settings,
                                           std::string* detail);

/// The expected error of the run's settings in the start-up report (expected_error_line).
class ExpectedErrorReport : public RunObserver {
 public:
  explicit ExpectedErrorReport(std::string line) : line_(std::move(line)) {}
  void start(Summary&, std::vector<std::string>& report) override { report.push_back(line_); }

 private:
  std::string line_;
};

}  // namespace rockcut::coupler
