// The scenes several integration tests run: the reduced dry cut, and a short cut of it on discs
// twice as large (a few seconds a run).
#pragma once

#include <string>
#include <vector>

#include "integration/process_helpers.hpp"

namespace rockcut::test {

inline const std::string kDryReducedScene = source("cases/cutting/dry_reduced.pbtxt");

/// --set overrides that make kDryReducedScene a short cut on coarse discs.
inline const std::vector<std::string> kSmallDryCut = {
    "--set", "dem.specimen.radius_min_m=0.0016", "--set", "dem.specimen.radius_max_m=0.0032",
    "--set", "time.end_time_s=0.008",            "--set", "dem.tool.steady_after_m=0.004",
    "--set", "output.frame_interval_s=0.002"};

}  // namespace rockcut::test
