// The headline numbers of a cutting run, from the DEM's step reports: mean tool forces over the
// steady part of the cut, break counts by mode, and chips.
//
// Steady part: the samples taken after the tool tip has travelled `dem.tool.steady_after_m` into
// the specimen (default two cutting depths: by then the first chip has formed and the force
// fluctuates about a stationary mean) until the end of the run.
// Signs: `force_horizontal_mean_n_per_m` is the force resisting the cut (-F_x of the rock on the
// tool), `force_vertical_mean_n_per_m` the vertical force of the rock on the tool, positive
// upwards (the paper's figure 8 convention: the tool must be pushed down into the rock).
// Under a damping that lets chips fly (dem.damping "viscous") the tool touches rock only part of
// the time: force_horizontal_peak_n_per_m is the largest resisting force of the steady part (what
// sizes a tooth) and tool_contact_fraction the share of its samples in which the tool touched any
// disc (force not exactly 0), and force_{horizontal,vertical}_mean_in_contact_n_per_m the means
// over those samples only: the force while the tool cuts, which the mean over all samples dilutes
// by the time it spends in the air between chips.
// The engineer's figures of the same steady part: force_horizontal_p95_n_per_m, the 95th percentile
// of the resisting force over the steady samples (linear interpolation between the order
// statistics at rank 0.95 (n - 1), numpy's default); force_horizontal_std_n_per_m, their standard
// deviation (population, divided by n); specific_energy_mpa, E_sp = F_h / (d w) = the mean resisting
// force per metre of width over the cut depth d [N/m^2 = J/m^3], written in MPa (= MJ/m^3): the
// work per volume of rock cut.
// Pressure nodes (coupled scenes): pressure_<node>_mean_pa is the mean over the steady samples of
// the node's average p - p_hydro (fluid_probe_<node>_pa), over the samples in which the node
// held at least one particle centre; pressure_<node>_samples counts them.
#pragma once

#include <cstdint>
#include <utility>
#include <string>
#include <vector>

#include "observers/run_observer.hpp"
#include "output/summary_json.hpp"
#include "wire/state_archive.hpp"
#include "rockcut/scene.pb.h"

namespace rockcut::coupler {

class CuttingSummary : public RowSummary {
 public:
  /// `node_names`: the pressure nodes whose probes the fluid reports (may be empty).
  CuttingSummary(const rockcut::Scene& scene, std::vector<std::string> node_names);
  bool active() const { return active_; }
  void observe(const std::vector<std::pair<std::string, double>>& scalars) override;
  void write(Summary& summary) const override;
  /// Checkpoint: the steady-part sums, the steady horizontal forces and the last sample.
  void save_state(state::StateArchive& a) const override;
  void load_state(const state::StateArchive& a) override;

 private:
  bool active_ = false;
  double steady_after_m_ = 0.0;
  double width_m_ = 0.0;
  double cut_depth_m_ = 0.0;
  double sum_x_ = 0.0, sum_y_ = 0.0;
  double peak_x_ = 0.0;
  std::uint64_t samples_ = 0, in_contact_ = 0;
  std::vector<double> steady_fh_;  // the resisting force of every steady sample, for p95 and std
  struct NodeMean {
    std::string name;
    std::string pa_key, particles_key;  // its time-series columns
    double sum_pa = 0.0;
    std::uint64_t samples = 0;
  };
  std::vector<NodeMean> nodes_;
  std::vector<std::pair<std::string, double>> last_;
};

}  // namespace rockcut::coupler
