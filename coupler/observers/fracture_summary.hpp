// The work of fracture of a double-edge-notched specimen pulled apart (scene dem.loading_test,
// kind `fracture`): Hillerborg's G_F, the work of the pulling ends until the specimen has come
// apart over the ligament's area (Hillerborg 1985, RILEM TC 50-FMC; per metre of thickness here).
// The DEM books the ends' work exactly every step (its energy ledger's boundary work); this
// observer reads it with the pull and the elongation at each time-series row.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "observers/run_observer.hpp"
#include "output/summary_json.hpp"
#include "rockcut/scene.pb.h"
#include "wire/state_archive.hpp"

namespace rockcut::coupler {

class FractureSummary : public RowSummary {
 public:
  explicit FractureSummary(const rockcut::Scene& scene);
  void observe(const std::vector<std::pair<std::string, double>>& scalars) override;
  void write(Summary& summary) const override;
  bool ends_run() const override { return stop_at_separation_ && separated_; }
  std::string end_reason(const RunClock& clock) const override;
  void save_state(state::StateArchive& a) const override;
  void load_state(const state::StateArchive& a) override;

  /// The specimen has come apart when, once the pull has fallen below half its peak, the ends'
  /// work over the last stretch as long as the elongation at the peak is below this fraction of
  /// the peak pull times that stretch: the mean pull over it, in which the halves' ringing
  /// averages out (their pull swings by a tenth of the peak under light dashpots).
  static constexpr double kSeparatedFraction = 0.02;
  static constexpr double kDroppedFraction = 0.5;

 private:
  bool stop_at_separation_ = true;
  bool separated_ = false;
  double ligament_m_ = 0.0;
  double peak_n_per_m_ = 0.0, peak_elongation_m_ = 0.0, work_at_peak_j_ = 0.0;
  // (elongation, work) of the samples since the pull fell below kDroppedFraction of its peak
  // (empty before), for the mean pull over the last stretch.
  std::vector<double> after_drop_;
  double work_j_ = 0.0;  // the latest sample's
  double separation_elongation_m_ = 0.0;
};

}  // namespace rockcut::coupler
