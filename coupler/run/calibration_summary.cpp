#include "run/calibration_summary.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rockcut::coupler {

namespace {
// The failure peak: the largest load before the load first falls below 80 % of the largest load
// so far. A damaged specimen may later be compacted to a higher load; that is not its strength.
// Drops while the load is still below 20 % of the test's largest are the platens seating on the
// specimen's rough ends (a few discs carry the first load and slip, most easily on frictionless
// platens), not failure.
constexpr double kFailureDrop = 0.8;
constexpr double kSeatingFraction = 0.2;

std::vector<CalibrationSummary::Sample>::const_iterator failure_peak(
    const std::vector<CalibrationSummary::Sample>& samples) {
  double largest = 0.0;
  for (const auto& s : samples) largest = std::max(largest, s.load);
  auto peak = samples.begin();
  for (auto it = samples.begin(); it != samples.end(); ++it) {
    if (it->load > peak->load) peak = it;
    if (peak->load >= kSeatingFraction * largest && it->load < kFailureDrop * peak->load) break;
  }
  return peak;
}

const double* find(const std::vector<std::pair<std::string, double>>& scalars, const char* name) {
  for (const auto& [k, v] : scalars) {
    if (k == name) return &v;
  }
  return nullptr;
}
}  // namespace

CalibrationSummary::CalibrationSummary(const rockcut::Scene& scene) {
  if (!scene.dem().has_loading_test()) return;
  active_ = true;
  ucs_ = scene.dem().loading_test().kind() == "ucs";
  if (scene.dem().has_specimen()) diameter_m_ = scene.dem().specimen().diameter_m();
}

void CalibrationSummary::observe(const std::vector<std::pair<std::string, double>>& scalars) {
  if (!active_) return;
  const double* strain = find(scalars, "axial_strain");
  const double* load = find(scalars, ucs_ ? "axial_stress_pa" : "platen_force_n_per_m");
  const double* lateral = find(scalars, "lateral_strain");
  if (!strain || !load) return;
  samples_.push_back({*strain, *load, lateral ? *lateral : 0.0});
}

bool CalibrationSummary::slopes_near_half_peak(const std::vector<Sample>& samples, double lo,
                                               double hi, double& load_slope,
                                               double& lateral_slope) {
  if (samples.empty()) return false;
  const auto peak = failure_peak(samples);
  double n = 0, sx = 0, sy = 0, sl = 0, sxx = 0, sxy = 0, sxl = 0;
  for (auto it = samples.begin(); it != peak; ++it) {
    if (it->load < lo * peak->load || it->load > hi * peak->load) continue;
    n += 1;
    sx += it->axial_strain;
    sy += it->load;
    sl += it->lateral_strain;
    sxx += it->axial_strain * it->axial_strain;
    sxy += it->axial_strain * it->load;
    sxl += it->axial_strain * it->lateral_strain;
  }
  const double det = n * sxx - sx * sx;
  if (n < 3 || det <= 0) return false;
  load_slope = (n * sxy - sx * sy) / det;
  lateral_slope = (n * sxl - sx * sl) / det;
  return true;
}

void CalibrationSummary::write(Summary& summary) const {
  if (!active_ || samples_.empty()) return;
  if (!ucs_) {
    // The splitting load is the largest platen force of the test: the disc's flat contacts crush
    // locally first (the load drops and rises again as the contact widens), and after the split
    // the halves carry little.
    double peak = 0.0;
    for (const Sample& s : samples_) peak = std::max(peak, s.load);
    // BTS = 2 F / (pi D t), F per unit thickness, t = 1 m.
    summary.set("bts_pa", 2.0 * peak / (std::numbers::pi * diameter_m_));
    summary.set("peak_force_n_per_m", peak);
    return;
  }
  const double peak = failure_peak(samples_)->load;
  summary.set("ucs_pa", peak);
  double e = 0.0, lateral = 0.0;
  if (slopes_near_half_peak(samples_, 0.4, 0.6, e, lateral)) {
    summary.set("youngs_modulus_pa", e);
    // Axial strain is positive in compression, lateral strain positive in extension.
    summary.set("poisson_ratio", lateral);
  }
}

}  // namespace rockcut::coupler
