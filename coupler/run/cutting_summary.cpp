#include "run/cutting_summary.hpp"

#include <algorithm>

namespace rockcut::coupler {

namespace {
const double* find(const std::vector<std::pair<std::string, double>>& scalars,
                   const std::string& name) {
  for (const auto& [k, v] : scalars) {
    if (k == name) return &v;
  }
  return nullptr;
}
}  // namespace

CuttingSummary::CuttingSummary(const rockcut::Scene& scene) {
  if (!scene.dem().has_tool()) return;
  const rockcut::Tool& tool = scene.dem().tool();
  active_ = true;
  steady_after_m_ = tool.steady_after_m() > 0 ? tool.steady_after_m() : 2.0 * tool.cutting_depth_m();
  width_m_ = tool.width_m();
}

void CuttingSummary::observe(const std::vector<std::pair<std::string, double>>& scalars) {
  if (!active_) return;
  last_ = scalars;
  const double* travel = find(scalars, "tool_travel_m");
  const double* fx = find(scalars, "tool_force_x_n_per_m");
  const double* fy = find(scalars, "tool_force_y_n_per_m");
  if (!travel || !fx || !fy || *travel < steady_after_m_) return;
  sum_x_ += -*fx;
  sum_y_ += *fy;
  ++samples_;
}

void CuttingSummary::write(Summary& summary) const {
  if (!active_) return;
  const double fh = samples_ ? sum_x_ / samples_ : 0.0;
  const double fv = samples_ ? sum_y_ / samples_ : 0.0;
  summary.set("force_horizontal_mean_n_per_m", fh);
  summary.set("force_vertical_mean_n_per_m", fv);
  summary.set("force_horizontal_mean_n", fh * width_m_);
  summary.set("force_vertical_mean_n", fv * width_m_);
  summary.set("steady_samples", static_cast<std::int64_t>(samples_));
  summary.set("steady_after_m", steady_after_m_);
  for (const char* key : {"breaks_tensile", "breaks_shear", "chips"}) {
    if (const double* v = find(last_, key)) summary.set(key, static_cast<std::int64_t>(*v));
  }
  if (const double* v = find(last_, "chip_area_mean_m2")) summary.set("chip_area_mean_m2", *v);
}

}  // namespace rockcut::coupler
