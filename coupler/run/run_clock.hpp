// Where a run stands: simulated time and step, the scalars of the last completed step, and what the
// exchanges have cost so far. The coupling scheme moves it on; the recorder, the observers and the
// checkpoints read it.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "rockcut/wire.pb.h"

namespace rockcut::coupler {

/// A module reported a tripped runtime guard (wire GuardTrip): the run stops as failed.
struct GuardStop {
  std::string module;  ///< label of the module that reported it
  wire::GuardTrip trip;
};

using NamedValues = std::vector<std::pair<std::string, double>>;

/// The value named `name` in `values`, or nullptr.
const double* find_value(const NamedValues& values, const std::string& name);

struct RunClock {
  double time_s = 0.0;
  std::uint64_t step = 0;
  std::uint64_t exchanges = 0;
  std::uint64_t bytes_exchanged = 0;
  std::uint64_t bytes_in_shared_memory = 0;  ///< the part the modules wrote to shared memory
  /// The last completed step's scalars: the DEM's step report and the fluid's (prefixed
  /// `fluid_`), sorted by name so every run writes the same columns.
  NamedValues scalars;
  /// Wall time of the earlier parts of a resumed run [s].
  double wall_before_s = 0.0;

  /// Takes the time, step and scalars of a step report (its scalars join those already in
  /// `scalars`); throws GuardStop naming `module` when the report carries a tripped guard.
  void take_step_report(const wire::StepReport& report, const std::string& module);
  /// The scalar `name` of the last completed step, or nullptr.
  const double* scalar(const std::string& name) const { return find_value(scalars, name); }
};

}  // namespace rockcut::coupler
