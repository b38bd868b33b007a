#include "observers/calibration_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
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
// The Brazilian disc has split when its load has fallen below half the largest so far while it
// opens across its horizontal diameter by more than 0.1 % of D (0.04 mm on the 40 mm disc).
// Measured on the as-printed disc: elastically the diameter grows by 3e-5 of D at 70 kN/m, thirty
// times less; local crushing under the platens drops the load without opening the mid-height
// diameter; a partial crack opens it by ~6e-4 while the load falls by 40 % and then rises again
// to the split. After the split the platens may crush the halves to a higher load, which is not
// the tensile strength.
constexpr double kSplitDrop = 0.5;
constexpr double kSplitOpening = 1e-3;

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
}  // namespace

CalibrationSummary::CalibrationSummary(const rockcut::Scene& scene) {
  if (!scene.dem().has_loading_test()) return;
  active_ = true;
  biaxial_ = scene.dem().loading_test().kind() == "biaxial";
  ucs_ = scene.dem().loading_test().kind() == "ucs" || biaxial_;
  if (scene.dem().has_specimen()) diameter_m_ = scene.dem().specimen().diameter_m();
  stop_at_split_ = !ucs_ && scene.dem().loading_test().stop_at_split();
}

void CalibrationSummary::observe(const std::vector<std::pair<std::string, double>>& scalars) {
  if (!active_) return;
  const double* strain = find_value(scalars, "axial_strain");
  const double* load = find_value(scalars, ucs_ ? "axial_stress_pa" : "platen_force_n_per_m");
  const double* lateral = find_value(scalars, "lateral_strain");
  const double* gauge = find_value(scalars, "axial_strain_gauge");
  if (!strain || !load) return;
  double deviator = *load;
  if (biaxial_) {
    const double* confining = find_value(scalars, "lateral_stress_pa");
    if (!confining) return;
    lateral_stress_pa_.push_back(*confining);
    deviator -= *confining;
  }
  samples_.push_back({*strain, deviator, lateral ? *lateral : 0.0, gauge ? *gauge : *strain});
  if (ucs_ || split_) return;
  const Sample& s = samples_.back();
  largest_load_ = std::max(largest_load_, s.load);
  if (s.load < kSplitDrop * largest_load_ && s.lateral_strain > kSplitOpening) {
    split_ = true;
    split_load_ = largest_load_;
    split_strain_ = s.axial_strain;
  }
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
    sx += it->gauge_strain;
    sy += it->load;
    sl += it->lateral_strain;
    sxx += it->gauge_strain * it->gauge_strain;
    sxy += it->gauge_strain * it->load;
    sxl += it->gauge_strain * it->lateral_strain;
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
    // The splitting load is the largest platen force before the split (kSplitDrop,
    // kSplitOpening). Without a split the largest load of the run is a lower bound.
    const double peak = split_ ? split_load_ : largest_load_;
    // BTS = 2 F / (pi D t), F per unit thickness, t = 1 m.
    summary.set("bts_pa", 2.0 * peak / (std::numbers::pi * diameter_m_));
    summary.set("peak_force_n_per_m", peak);
    summary.set("split_detected", split_);
    if (split_) summary.set("split_axial_strain", split_strain_);
    return;
  }
  const auto peak_sample = failure_peak(samples_);
  const double peak = peak_sample->load;
  if (biaxial_) {
    const double confining = lateral_stress_pa_[peak_sample - samples_.begin()];
    summary.set("peak_axial_stress_pa", peak + confining);
    summary.set("confining_stress_pa", confining);
    summary.set("peak_deviator_stress_pa", peak);
    summary.set("peak_axial_strain", peak_sample->axial_strain);
    // The residual strength: the mean axial stress over the last fifth of the run's strain.
    const double last_strain = samples_.back().axial_strain;
    const double from = peak_sample->axial_strain + 0.8 * (last_strain - peak_sample->axial_strain);
    double sum = 0.0;
    int n = 0;
    for (auto it = peak_sample + 1; it != samples_.end(); ++it) {
      if (it->axial_strain < from) continue;
      sum += it->load + lateral_stress_pa_[it - samples_.begin()];
      ++n;
    }
    if (n > 0) summary.set("residual_axial_stress_pa", sum / n);
  } else {
    summary.set("ucs_pa", peak);
  }
  double e = 0.0, lateral = 0.0;
  if (slopes_near_half_peak(samples_, 0.4, 0.6, e, lateral)) {
    summary.set("youngs_modulus_pa", e);
    // Axial strain is positive in compression, lateral strain positive in extension.
    summary.set("poisson_ratio", lateral);
  }
}

void CalibrationSummary::save_state(state::StateArchive& a) const {
  a.put("calibration_split", std::vector<double>{split_ ? 1.0 : 0.0, largest_load_, split_load_,
                                                 split_strain_});
  std::vector<double> samples;
  for (const Sample& s : samples_) {
    samples.insert(samples.end(), {s.axial_strain, s.load, s.lateral_strain, s.gauge_strain});
  }
  a.put("calibration_samples", std::move(samples), 4);
  if (biaxial_) a.put("calibration_lateral_stress_pa", lateral_stress_pa_);
}

void CalibrationSummary::load_state(const state::StateArchive& a) {
  const auto split = a.values("calibration_split", 4);
  split_ = split[0] != 0.0;
  largest_load_ = split[1];
  split_load_ = split[2];
  split_strain_ = split[3];
  const auto samples = a.values("calibration_samples");
  samples_.clear();
  for (std::size_t k = 0; k + 3 < samples.size(); k += 4) {
    samples_.push_back({samples[k], samples[k + 1], samples[k + 2], samples[k + 3]});
  }
  if (biaxial_) a.get("calibration_lateral_stress_pa", lateral_stress_pa_, samples_.size());
}

std::string CalibrationSummary::end_reason(const RunClock& clock) const {
  char line[160];
  std::snprintf(line, sizeof line,
                "the Brazilian disc split at t = %.6g s: test ended (loading_test.stop_at_split)",
                clock.time_s);
  return line;
}

}  // namespace rockcut::coupler
