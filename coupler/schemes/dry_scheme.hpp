// The DEM alone (a dry scene: no fluid process). Each exchange is one Advance of as many steps as
// lie before the next record, so a dry run costs one message per record, not one per step. The
// Verlet half-steps of the paper's eqs. 5-8 then all run inside the DEM (DESIGN section 3: with
// no fluid force there is nothing to split the step for).
#pragma once

#include "schemes/coupling_scheme.hpp"

namespace rockcut::coupler {

class DryScheme : public CouplingScheme {
 public:
  DryScheme(const TimePlan& plan, RunModules& modules) : CouplingScheme(plan), modules_(modules) {}
  const char* name() const override { return "dry"; }
  void initialise(RunClock& clock) override { advance_steps(clock, 0); }
  std::uint64_t regular_steps(const RunClock& clock,
                              const ExchangeSchedule& schedule) const override;
  void advance(RunClock& clock, unsigned steps, const ExchangeSchedule&) override {
    advance_steps(clock, steps);
  }
  bool between_steps() const override { return true; }

 private:
  /// One Advance of `steps` full steps (0: the forces at t = 0).
  void advance_steps(RunClock& clock, unsigned steps);

  RunModules& modules_;
};

}  // namespace rockcut::coupler
