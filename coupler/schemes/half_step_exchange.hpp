// The paper's two-way coupling (section 3.2, figure 5) made multi-rate: DESIGN section 3. Per
// exchange, with N DEM steps per fluid step:
//  1. the DEM runs N-1 full Verlet steps and the first half of the last one (half kick, drift) and
//     answers x^{n+N} and v^{n+N-1/2};
//  2. the fluid advances the pore pressure by N dt from them and answers the force on each grain;
//  3. the DEM completes the step with its contact forces plus that force (second half kick).
// Step 3 rides on the next exchange's Advance unless the step is recorded or checkpointed: two
// round trips per exchange instead of three, with the same arithmetic. N = 1 is the paper's scheme.
#pragma once

#include "schemes/coupling_scheme.hpp"

namespace rockcut::coupler {

class HalfStepExchange : public CouplingScheme {
 public:
  HalfStepExchange(const TimePlan& plan, RunModules& modules, const RunObservers& observers);
  const char* name() const override { return "half-step exchange"; }
  /// t = 0: the fluid's force at the initial positions, so that a^0 includes it.
  void initialise(RunClock& clock) override { exchange(clock, 0, true, nullptr); }
  std::uint64_t regular_steps(const RunClock&, const ExchangeSchedule&) const override {
    return plan_.coupling_interval;
  }
  void advance(RunClock& clock, unsigned steps, const ExchangeSchedule& schedule) override {
    exchange(clock, steps, false, &schedule);
  }
  bool between_steps() const override { return !forces_held_; }

 private:
  void exchange(RunClock& clock, unsigned steps, bool initial, const ExchangeSchedule* schedule);

  RunModules& modules_;
  RunModule& dem_;
  RunModule& fluid_;
  const RunObservers& observers_;
  bool forces_held_ = false;  // fluid_.reply holds forces the next Advance applies first
};

}  // namespace rockcut::coupler
