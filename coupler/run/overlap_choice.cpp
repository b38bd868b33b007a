#include "run/overlap_choice.hpp"

#include <sched.h>

#include <thread>

namespace rockcut::coupler {

OverlapChoice choose_overlap(const std::string& setting, Transport transport,
                             unsigned dem_threads, unsigned fluid_threads, unsigned cores) {
  const std::string threads = "dem.threads " + std::to_string(dem_threads) + " + fluid.threads " +
                              std::to_string(fluid_threads) + " on " + std::to_string(cores) +
                              (cores == 1 ? " core" : " cores");
  OverlapChoice c;
  if (setting == "on" || setting == "off") {
    c.overlap = setting == "on";
    c.report = std::string("overlap    ") +
               (c.overlap ? "the DEM's forces overlap the fluid's step"
                          : "the DEM's forces and the fluid's step take turns") +
               " (coupling.overlap \"" + setting + "\"; " + threads + ")";
    return c;
  }
  if (transport == Transport::tcp) {
    c.report = "overlap    the DEM's forces overlap the fluid's step (coupling.overlap \"auto\": "
               "over tcp the modules may have cores of their own)";
    return c;
  }
  const bool idle_cores = dem_threads + fluid_threads <= cores;
  c.overlap = idle_cores || cores >= kManyCores;
  c.report = std::string("overlap    ") +
             (c.overlap ? "the DEM's forces overlap the fluid's step (coupling.overlap \"auto\": "
                        : "the DEM's forces and the fluid's step take turns (coupling.overlap "
                          "\"auto\": ") +
             threads +
             (idle_cores || !c.overlap ? ")"
                                       : "; from 16 cores the step's serial parts hide behind "
                                         "the other module's work)");
  return c;
}

unsigned usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) {
    const int n = CPU_COUNT(&set);
    if (n > 0) return static_cast<unsigned>(n);
  }
  const unsigned n = std::thread::hardware_concurrency();
  return n > 0 ? n : 1;
}

}  // namespace rockcut::coupler
