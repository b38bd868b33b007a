// Fragments: connected clusters of bonded discs. The largest is the specimen; every other cluster
// of at least two discs is a chip detached from it (single discs are crushed debris).
#pragma once

#include <cstdint>
#include <vector>

#include "core/bonds.hpp"
#include "core/particles.hpp"

namespace rockcut::dem {

struct ChipStats {
  std::size_t chips = 0;          ///< clusters of >= 2 discs other than the largest
  double mean_area_m2 = 0.0;      ///< mean solid area of a chip (sum of pi r^2) [m^2 per m]
};

ChipStats chip_stats(const Particles& p, const BondSet& bonds);

}  // namespace rockcut::dem
