// Whether the DEM's forces overlap the fluid's step (scene coupling.overlap): worth it where the
// cores would otherwise idle, or where there are so many that each step's serial parts (messages,
// array copies, the fluid's geometry) cost more than the teams' time-sharing. Measured on the
// paper-scale dynamic saturated cut (docs/performance.md, "Overlap"): 2 + 2 threads on 2 cores
// overlapping took 1.09-1.17 times the wall of taking turns; 16 + 16 on 16 cores 0.79.
#pragma once

#include <string>

#include "run/module_link.hpp"

namespace rockcut::coupler {

struct OverlapChoice {
  bool overlap = true;
  std::string report;  ///< one start-up line: the choice and why
};

/// From this many cores "auto" overlaps whatever the thread counts.
inline constexpr unsigned kManyCores = 16;

/// `setting` "on", "off" or "auto" (on over tcp; over ipc and inproc, on when dem_threads +
/// fluid_threads <= cores or cores >= kManyCores).
OverlapChoice choose_overlap(const std::string& setting, Transport transport,
                             unsigned dem_threads, unsigned fluid_threads, unsigned cores);

/// The cores this process may run on (its affinity mask, as Slurm's --cpus-per-task sets it);
/// at least 1.
unsigned usable_cores();

}  // namespace rockcut::coupler
