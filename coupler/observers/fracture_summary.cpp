#include "observers/fracture_summary.hpp"

#include <cmath>
#include <cstdio>

namespace rockcut::coupler {

FractureSummary::FractureSummary(const rockcut::Scene& scene)
    : stop_at_separation_(scene.dem().loading_test().stop_at_split()) {}

void FractureSummary::observe(const std::vector<std::pair<std::string, double>>& scalars) {
  const double* pull = find_value(scalars, "pulling_force_n_per_m");
  const double* elongation = find_value(scalars, "elongation_m");
  const double* ligament = find_value(scalars, "ligament_m");
  const double* work = find_value(scalars, "boundary_work_j");
  if (!pull || !elongation || !ligament || !work || separated_) return;
  ligament_m_ = *ligament;
  work_j_ = *work;
  // The peak is the largest pull so far. A dip at the start (the first samples of a specimen
  // settling) may count as the drop; the mean pull over the stretch since then stays at the
  // rising pull, so it cannot end the test.
  if (*pull > peak_n_per_m_) {
    peak_n_per_m_ = *pull;
    peak_elongation_m_ = *elongation;
    work_at_peak_j_ = *work;
  }
  if (after_drop_.empty() && *pull >= kDroppedFraction * peak_n_per_m_) return;
  after_drop_.insert(after_drop_.end(), {*elongation, *work});
  // The latest sample at least one peak elongation back.
  const double from_m = *elongation - peak_elongation_m_;
  std::size_t k = after_drop_.size();
  while (k >= 2 && after_drop_[k - 2] > from_m) k -= 2;
  if (k < 2) return;  // not a stretch that long since the drop yet
  const double stretch_m = *elongation - after_drop_[k - 2];
  if (*work - after_drop_[k - 1] < kSeparatedFraction * peak_n_per_m_ * stretch_m) {
    separated_ = true;
    separation_elongation_m_ = after_drop_[k - 2];
  }
}

void FractureSummary::write(Summary& summary) const {
  if (ligament_m_ <= 0) return;
  // Per metre of thickness: J/m over m is J/m^2, N/m over m is Pa.
  summary.set("fracture_energy_j_per_m2", work_j_ / ligament_m_);
  summary.set("work_to_peak_j_per_m2", work_at_peak_j_ / ligament_m_);
  summary.set("net_tensile_strength_pa", peak_n_per_m_ / ligament_m_);
  summary.set("peak_force_n_per_m", peak_n_per_m_);
  summary.set("peak_elongation_m", peak_elongation_m_);
  summary.set("ligament_m", ligament_m_);
  summary.set("separated", separated_);
  if (separated_) summary.set("separation_elongation_m", separation_elongation_m_);
}

void FractureSummary::save_state(state::StateArchive& a) const {
  a.put("fracture_summary",
        std::vector<double>{separated_ ? 1.0 : 0.0, ligament_m_, peak_n_per_m_, peak_elongation_m_,
                            work_at_peak_j_, work_j_, separation_elongation_m_});
  a.put("fracture_after_drop", after_drop_, 2);
}

void FractureSummary::load_state(const state::StateArchive& a) {
  const auto v = a.values("fracture_summary", 7);
  separated_ = v[0] != 0.0;
  ligament_m_ = v[1];
  peak_n_per_m_ = v[2];
  peak_elongation_m_ = v[3];
  work_at_peak_j_ = v[4];
  work_j_ = v[5];
  separation_elongation_m_ = v[6];
  a.get("fracture_after_drop", after_drop_);
}

std::string FractureSummary::end_reason(const RunClock& clock) const {
  char line[160];
  std::snprintf(line, sizeof line,
                "the notched specimen came apart at t = %.6g s: test ended "
                "(loading_test.stop_at_split)",
                clock.time_s);
  return line;
}

}  // namespace rockcut::coupler
