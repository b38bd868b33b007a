#include "run/expected_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>

namespace rockcut::coupler {

namespace {

// docs/accuracy.md: errors of the mean over seeds against the finest setting of each ladder
// (scripts/accuracy, the reduced saturated cut at 0 m, 24 mm). Coarsest first, finest (0) last.
struct LadderPoint {
  double value;
  double force_error;   ///< relative error of the mean horizontal force
};
// The default rock (set H): seeds 1-4 and 14 mm of steady cut. The seed scatter of each mean is 6-14 % (docs/accuracy.md), so errors below about 15 % are
// upper bounds more than estimates.
constexpr LadderPoint kDtSafety[] = {{0.4, 0.09}, {0.2, 0.08}, {0.1, 0.08}, {0.05, 0.13},
                                     {0.025, 0.0}};
// N dt / the stiffness limit (N x 0.0705 in the study). The coarsest is the largest N the limit
// allows (N = 14, 0.987 of the limit; seeds 1-4): any stable N lies at or below 1. N = 10 down to
// N = 1 (no lag, the finest) are the interval study at 0 m (docs/accuracy.md, "The coupling
// interval over sixteen seeds"): 0.42, 0.33, 0.10, 0.09, 0.00 at N = 10, 7, 5, 3, 2 (N = 7 and 2
// over seeds 1-8, the others over seeds 1-16; standard errors 7-11 %).
constexpr LadderPoint kFluidStepRatio[] = {{1.0, 0.54},   {0.705, 0.42}, {0.493, 0.33},
                                           {0.352, 0.10}, {0.211, 0.09}, {0.141, 0.0},
                                           {0.0705, 0.0}};
constexpr LadderPoint kHPerDiameter[] = {{3.33, 0.15}, {2.5, 0.04}, {1.67, 0.0}};
constexpr LadderPoint kSizeScale[] = {{1.5, 0.31}, {1.0, 0.08}, {0.75, 0.16}, {0.5, 0.0}};
// The reduced scene's mean radius, the size ladder's 1.
constexpr double kStudyMeanRadiusM = 1.2e-3;

// The error at `value`, linear in log(value) between the ladder's settings. A value finer than the
// finest gets the finest's 0 (the study cannot resolve it); coarser than the coarsest: none.
std::optional<double> interpolate(std::span<const LadderPoint> ladder, double value) {
  const bool descending = ladder.front().value > ladder.back().value;
  const auto coarser = [&](double a, double b) { return descending ? a > b : a < b; };
  if (coarser(value, ladder.front().value * (1 + 1e-9))) return std::nullopt;
  if (!coarser(value, ladder.back().value)) return 0.0;
  for (std::size_t k = 0; k + 1 < ladder.size(); ++k) {
    const LadderPoint& a = ladder[k];
    const LadderPoint& b = ladder[k + 1];
    if (coarser(value, b.value) && !coarser(value, a.value * (1 + 1e-9))) {
      const double s = std::log(value / a.value) / std::log(b.value / a.value);
      return a.force_error + s * (b.force_error - a.force_error);
    }
  }
  return std::nullopt;
}

std::string percent(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.0f %%", 100 * v);
  return b;
}

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

}  // namespace

std::optional<double> expected_force_error(const CutSettings& s, std::string* detail) {
  struct Part {
    const char* name;
    std::span<const LadderPoint> ladder;
    double value;
  };
  const Part parts[] = {{"dt_safety", kDtSafety, s.dt_safety},
                        {"fluid step / stiffness limit", kFluidStepRatio, s.fluid_step_ratio},
                        {"h / mean diameter", kHPerDiameter, s.h_per_diameter},
                        {"disc size / reduced scene's", kSizeScale, s.size_scale}};
  double sum2 = 0.0;
  std::string text;
  for (const Part& p : parts) {
    const std::optional<double> e = interpolate(p.ladder, p.value);
    if (!e) {
      if (detail) {
        *detail = std::string(p.name) + " = " + number(p.value) +
                  " is coarser than the study covers (" + number(p.ladder.front().value) + ")";
      }
      return std::nullopt;
    }
    sum2 += *e * *e;
    text += (text.empty() ? "" : ", ") + percent(*e) + " from " + p.name + " " + number(p.value);
  }
  if (detail) *detail = text;
  return std::sqrt(sum2);
}

std::optional<std::string> expected_error_line(const rockcut::Scene& scene, const TimePlan& plan,
                                               double dem_limit_s, double fluid_stiffness_limit_s) {
  if (!scene.has_fluid() || !scene.dem().has_tool() || !scene.dem().has_specimen()) {
    return std::nullopt;
  }
  const rockcut::Specimen& sp = scene.dem().specimen();
  CutSettings s;
  s.dt_safety = dem_limit_s > 0 ? plan.dt_s / dem_limit_s : 0.0;
  s.fluid_step_ratio = plan.coupling_interval > 1 && fluid_stiffness_limit_s > 0
                           ? plan.coupling_interval * plan.dt_s / fluid_stiffness_limit_s
                           : 0.0;
  s.h_per_diameter = scene.fluid().smoothing_length_m() / (sp.radius_min_m() + sp.radius_max_m());
  s.size_scale = 0.5 * (sp.radius_min_m() + sp.radius_max_m()) / kStudyMeanRadiusM;
  std::string detail;
  const std::optional<double> e = expected_force_error(s, &detail);
  if (!e) return "accuracy   not covered by the work-precision study (docs/accuracy.md): " + detail;
  return "accuracy   expected error of the mean horizontal force about " + percent(*e) +
         " (root sum square of " + detail + "; docs/accuracy.md, against the study's finest "
         "settings)";
}

}  // namespace rockcut::coupler
