// Where a run's wall time went: each module's step by phase, its service work (messages,
// reports, guards), the coupler's waits on each module, and the coupler's own work (output,
// observers, the scheme's bookkeeping). Into summary.json, and one line on stdout.
#pragma once

#include "output/summary_json.hpp"
#include "session/run_parts.hpp"

namespace rockcut::coupler {

/// Sets dem_phase_<name>_s, dem_service_s, dem_request_s (and the fluid's) and coupler_own_s
/// in `summary`, for the loop of this invocation (`loop_wall_s`), and prints the split.
void report_time_split(const RunParts& run, Summary& summary, double loop_wall_s);

/// Sets dem_neighbour_rebuilds and fluid_geometry_updates, _local_updates, _rows_recomputed
/// (since the run's start, over resumes) where the modules report them, and prints one line.
void report_rebuilds(const RunClock& clock, Summary& summary);

}  // namespace rockcut::coupler
