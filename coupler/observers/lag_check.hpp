// Where the coupling lag's correction (Coupling.lag_correction "passivity") did the pore fluid's
// dissipation. Per window of the tool's travel it compares what the correction took out with what
// the pore fluid dissipated; where the correction took more, the lag generated energy faster than
// Darcy flow dissipates it, and the run's energy there is the correction's, not the fluid's. Over
// 5 mm windows that happened in 1 of 24 windows of the paper-scale cut at N = 8 (one seed's
// fluid putting work in over 3 mm); on the reduced cut in none of 112 at N = 8 at 0 and at
// 2000 m (nor in the default scene's 33), in 6 and 2 of 112 at N = 10 and in 46 and 50 at
// N = 16, the N the study turned down on the energy (docs/record/results.md, "The lag's energy
// taken out at paper scale").
#pragma once

#include <cstdint>

#include "observers/run_observer.hpp"

namespace rockcut::coupler {

class LagCheck : public RunObserver {
 public:
  /// The window of the tool's travel [m]: several chips at either scale, so a window's fluid
  /// work is a cut's, not one fragment's.
  static constexpr double kWindowM = 0.005;
  /// A window whose correction is below this share of the tool's work so far is not counted:
  /// where the tool cuts air after a chip has gone, loose fragments trade a few J/m with the
  /// fluid, and the default scene would count 6 of its 33 windows against the window's own work.
  static constexpr double kNegligibleShare = 0.01;

  void row(const RunClock& clock) override;
  bool finish(const RunClock& clock, Summary& summary, bool completed) override;
  void save_state(state::StateArchive& a) const override;
  void load_state(const state::StateArchive& a) override;

  std::uint64_t windows() const { return windows_; }
  std::uint64_t resolved_windows() const { return resolved_; }
  /// The tool's travel where the first such window starts [m]; negative when none.
  double first_resolved_m() const { return first_resolved_m_; }

 private:
  bool started_ = false;
  double start_travel_m_ = 0.0;  ///< where the window starts [m]
  double start_correction_j_ = 0.0;  ///< the ledger's terms there [J/m]
  double start_fluid_work_j_ = 0.0;
  std::uint64_t windows_ = 0;
  std::uint64_t resolved_ = 0;
  double first_resolved_m_ = -1.0;
};

}  // namespace rockcut::coupler
