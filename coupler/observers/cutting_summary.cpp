#include "observers/cutting_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "run/named_values_state.hpp"
#include "scene/tool_geometry.hpp"

namespace rockcut::coupler {

CuttingSummary::CuttingSummary(const rockcut::Scene& scene, std::vector<std::string> node_names) {
  if (!scene.dem().has_tool()) return;
  for (std::string& name : node_names) {
    nodes_.push_back({name, "fluid_probe_" + name + "_pa", "fluid_probe_" + name + "_particles"});
  }
  const rockcut::Tool& tool = scene.dem().tool();
  active_ = true;
  steady_after_m_ = rockcut::scene::tool_steady_after_m(tool);
  width_m_ = tool.width_m();
  cut_depth_m_ = tool.cutting_depth_m();
}

namespace {
// The p-quantile with linear interpolation between order statistics at rank p (n - 1).
double quantile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double rank = p * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(rank));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (rank - static_cast<double>(below)) * (values[above] - values[below]);
}

double standard_deviation(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= static_cast<double>(values.size());
  double sum = 0.0;
  for (double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(values.size()));
}
}  // namespace

void CuttingSummary::observe(const std::vector<std::pair<std::string, double>>& scalars) {
  if (!active_) return;
  last_ = scalars;
  const double* travel = find_value(scalars, "tool_travel_m");
  const double* fx = find_value(scalars, "tool_force_x_n_per_m");
  const double* fy = find_value(scalars, "tool_force_y_n_per_m");
  if (!travel || !fx || !fy || *travel < steady_after_m_) return;
  sum_x_ += -*fx;
  sum_y_ += *fy;
  peak_x_ = std::max(peak_x_, -*fx);
  steady_fh_.push_back(-*fx);
  in_contact_ += (*fx != 0.0 || *fy != 0.0);
  ++samples_;
  for (NodeMean& node : nodes_) {
    const double* p = find_value(scalars, node.pa_key);
    const double* n = find_value(scalars, node.particles_key);
    if (!p || !n || *n < 1) continue;
    node.sum_pa += *p;
    ++node.samples;
  }
}

void CuttingSummary::write(Summary& summary) const {
  if (!active_) return;
  // A run that stopped before the steady part has no steady statistics: NaN, written as null, so
  // that no 0 N/m is read as the rock's force (and sweep tables leave the run out).
  const double none = std::numeric_limits<double>::quiet_NaN();
  const double n = static_cast<double>(samples_);
  const double fh = samples_ ? sum_x_ / n : none;
  const double fv = samples_ ? sum_y_ / n : none;
  summary.set("force_horizontal_mean_n_per_m", fh);
  summary.set("force_vertical_mean_n_per_m", fv);
  summary.set("force_horizontal_mean_n", fh * width_m_);
  summary.set("force_vertical_mean_n", fv * width_m_);
  summary.set("force_horizontal_peak_n_per_m", samples_ ? peak_x_ : none);
  summary.set("force_horizontal_p95_n_per_m", samples_ ? quantile(steady_fh_, 0.95) : none);
  summary.set("force_horizontal_std_n_per_m", samples_ ? standard_deviation(steady_fh_) : none);
  summary.set("specific_energy_mpa", fh / cut_depth_m_ * 1e-6);
  summary.set("tool_contact_fraction", samples_ ? static_cast<double>(in_contact_) / n : none);
  // While cutting: a sample without contact has a force of exactly 0, so the sums over all samples
  // are the sums over the contact samples. Without a contact sample there is no such mean.
  const double contact = static_cast<double>(in_contact_);
  summary.set("force_horizontal_mean_in_contact_n_per_m", in_contact_ ? sum_x_ / contact : none);
  summary.set("force_vertical_mean_in_contact_n_per_m", in_contact_ ? sum_y_ / contact : none);
  summary.set("steady_samples", static_cast<std::int64_t>(samples_));
  summary.set("steady_after_m", steady_after_m_);
  for (const char* key : {"breaks_tensile", "breaks_shear", "chips"}) {
    if (const double* v = find_value(last_, key)) summary.set(key, static_cast<std::int64_t>(*v));
  }
  if (const double* v = find_value(last_, "chip_area_mean_m2")) summary.set("chip_area_mean_m2", *v);
  for (const NodeMean& node : nodes_) {
    summary.set("pressure_" + node.name + "_mean_pa",
                node.samples ? node.sum_pa / static_cast<double>(node.samples) : none);
    summary.set("pressure_" + node.name + "_samples", static_cast<std::int64_t>(node.samples));
  }
}

void CuttingSummary::save_state(state::StateArchive& a) const {
  a.put("cutting_sums", std::vector<double>{sum_x_, sum_y_, static_cast<double>(samples_), peak_x_,
                                            static_cast<double>(in_contact_)});
  std::vector<double> nodes;
  for (const NodeMean& n : nodes_) nodes.insert(nodes.end(), {n.sum_pa, static_cast<double>(n.samples)});
  a.put("cutting_node_sums", std::move(nodes), 2);
  a.put("cutting_steady_fh", std::span<const double>(steady_fh_));
  save_named_values(a, "cutting_last", last_);
}

void CuttingSummary::load_state(const state::StateArchive& a) {
  const auto sums = a.values("cutting_sums", 5);
  sum_x_ = sums[0];
  sum_y_ = sums[1];
  samples_ = static_cast<std::uint64_t>(sums[2]);
  peak_x_ = sums[3];
  in_contact_ = static_cast<std::uint64_t>(sums[4]);
  const auto nodes = a.values("cutting_node_sums", 2 * nodes_.size());
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    nodes_[k].sum_pa = nodes[2 * k];
    nodes_[k].samples = static_cast<std::uint64_t>(nodes[2 * k + 1]);
  }
  a.get("cutting_steady_fh", steady_fh_, samples_);
  last_ = load_named_values(a, "cutting_last");
}

}  // namespace rockcut::coupler
