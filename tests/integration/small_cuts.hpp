// The scenes several integration tests run: the reduced dry cut, and a short cut of it.
#pragma once

#include <string>
#include <vector>

#include "integration/process_helpers.hpp"

namespace rockcut::test {

inline const std::string kDryReducedScene = source("cases/cutting/dry_reduced.pbtxt");

/// The small cut: --set overrides that make kDryReducedScene's discs twice as coarse (radius
/// 1.6-3.2 mm: about 150 discs, and twice the time step), 7 mm of tool travel (t = 8 ms; the tip
/// starts 1 mm before the block) and the steady part from 4 mm. On this packing the first bonds
/// break at about 3 mm of travel and about 25 have broken by 6 mm, so the run has breaks and
/// steady samples. About 60,000 steps: under a second with one thread.
inline const std::vector<std::string> kSmallDryCut = {"--set", "dem.specimen.radius_min_m=0.0016",
                                                      "--set", "dem.specimen.radius_max_m=0.0032",
                                                      "--set", "time.end_time_s=0.008",
                                                      "--set", "dem.tool.steady_after_m=0.004",
                                                      "--set", "output.frame_interval_s=0.002"};

}  // namespace rockcut::test
