// Whether the DEM's forces overlap the fluid's step (scene coupling.overlap): worth it only where
// the cores would otherwise idle. Measured on the paper-scale saturated cut, 2 + 2 threads on 2
// cores: overlapping took 1.17 times the wall of taking turns (docs/performance.md, "Overlap").
#pragma once

#include <string>

#include "run/module_link.hpp"

namespace rockcut::coupler {

struct OverlapChoice {
  bool overlap = true;
  std::string report;  ///< one start-up line: the choice and why
};

/// `setting` "on", "off" or "auto" (on over tcp; over ipc and inproc, on when dem_threads +
/// fluid_threads <= cores).
OverlapChoice choose_overlap(const std::string& setting, Transport transport,
                             unsigned dem_threads, unsigned fluid_threads, unsigned cores);

/// The cores this process may run on (its affinity mask, as Slurm's --cpus-per-task sets it);
/// at least 1.
unsigned usable_cores();

}  // namespace rockcut::coupler
