// The results of a calibration test (scene block dem.loading_test), from the DEM's step reports:
// UCS, Young's modulus and Poisson's ratio for `ucs`, the Brazilian tensile strength for
// `brazilian`, the peak and residual strength under a confining stress for `biaxial` (definitions
// in proto/rockcut/scene.proto, message LoadingTest).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "observers/run_observer.hpp"
#include "output/summary_json.hpp"
#include "wire/state_archive.hpp"
#include "rockcut/scene.pb.h"

namespace rockcut::coupler {

class CalibrationSummary : public RowSummary {
 public:
  explicit CalibrationSummary(const rockcut::Scene& scene);
  bool active() const { return active_; }
  void observe(const std::vector<std::pair<std::string, double>>& scalars) override;
  void write(Summary& summary) const override;
  bool ends_run() const override { return test_over(); }
  std::string end_reason(const RunClock& clock) const override;
  /// Checkpoint: the samples and the split detector.
  void save_state(state::StateArchive& a) const override;
  void load_state(const state::StateArchive& a) override;
  /// True once a Brazilian disc has split and the scene asks to stop there (stop_at_split).
  bool test_over() const { return stop_at_split_ && split_; }

  struct Sample {
    // load: stress [Pa] (ucs; biaxial: the deviator stress, axial minus lateral) or force [N/m]
    double axial_strain, load, lateral_strain;
    // UCS: the axial strain over the specimen's middle half (axial_strain_gauge), which E and nu
    // are fitted against; the platens' strain where the DEM reports no gauge.
    double gauge_strain;
  };
  /// Least-squares slopes of load and lateral strain against gauge strain over the samples before
  /// the failure peak whose load lies in [lo, hi] times the peak. The failure peak is the largest
  /// load before the load first drops below 80 % of the largest so far. Returns false with fewer than 3 samples.
  static bool slopes_near_half_peak(const std::vector<Sample>& samples, double lo, double hi,
                                    double& load_slope, double& lateral_slope);

 private:
  bool active_ = false;
  bool ucs_ = true;      // ucs or biaxial: a stress-strain curve
  bool biaxial_ = false;
  double diameter_m_ = 0.0;
  bool stop_at_split_ = false;
  // Brazilian split detector, updated by observe().
  bool split_ = false;
  double largest_load_ = 0.0;
  double split_load_ = 0.0, split_strain_ = 0.0;
  std::vector<Sample> samples_;
  std::vector<double> lateral_stress_pa_;  // biaxial: sigma_3 of each sample
};

}  // namespace rockcut::coupler
