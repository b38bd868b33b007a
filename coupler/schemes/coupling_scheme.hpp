// How a run advances: one coupling scheme per way of driving the modules (DESIGN section 3). The
// run loop asks its scheme for one exchange at a time and never branches on the kind of scene;
// a new scheme (an implicit or stiffness-aware exchange, docs/accuracy.md) is one more class.
#pragma once

#include <cstdint>
#include <memory>

#include "observers/run_observer.hpp"
#include "run/run_clock.hpp"
#include "run/run_modules.hpp"
#include "run/time_plan.hpp"

namespace rockcut::coupler {

/// What the run needs of the next exchanges: where a step must be completed because it is
/// recorded or checkpointed, and how far the next record is.
class ExchangeSchedule {
 public:
  /// Whether the step ending at (`step`, `time_s`) must be completed within its exchange.
  virtual bool completes_step_at(std::uint64_t step, double time_s) const = 0;
  /// Steps from (`step`, `time_s`) to the next time-series row or frame (at least 1).
  virtual std::uint64_t steps_to_next_record(std::uint64_t step, double time_s) const = 0;

 protected:
  ~ExchangeSchedule() = default;
};

class CouplingScheme {
 public:
  explicit CouplingScheme(const TimePlan& plan) : plan_(plan) {}
  virtual ~CouplingScheme() = default;
  /// For the start-up report and summary.json.
  virtual const char* name() const = 0;
  /// A fresh run's exchange at t = 0: the first forces and the first scalars.
  virtual void initialise(RunClock& clock) = 0;
  /// The steps of the next exchange when the end of the run does not cut it short.
  virtual std::uint64_t regular_steps(const RunClock& clock,
                                      const ExchangeSchedule& schedule) const = 0;
  /// One exchange of `steps` DEM steps.
  virtual void advance(RunClock& clock, unsigned steps, const ExchangeSchedule& schedule) = 0;
  /// Whether the modules hold whole steps now (no force waits for the next exchange): only then
  /// can their states be saved.
  virtual bool between_steps() const = 0;
  /// The run has reached its end time.
  bool done(const RunClock& clock) const { return clock.step >= plan_.total_steps; }

 protected:
  const TimePlan& plan_;
};

/// The scheme the scene asks for: the half-step exchange when it has a fluid, the DEM alone when
/// it is dry.
std::unique_ptr<CouplingScheme> make_coupling_scheme(const rockcut::Scene& scene,
                                                     const TimePlan& plan, RunModules& modules,
                                                     const RunObservers& observers);

}  // namespace rockcut::coupler
