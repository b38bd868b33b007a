// A flexible membrane's pressure on the sides of a specimen: the confinement of a biaxial test as a
// triaxial cell's rubber sleeve gives it. The side of a specimen cut from a random packing is
// rough; a rigid wall pressed on it carries the confining stress on the few discs that stand out,
// which crush first (as on rough platens: docs/calibration.md). The membrane instead pushes the
// outermost disc of every band of the side, each band 2 r_max high, with the band's share
// sigma_c H / n: the same line load all along the side, a dead load that follows the discs.
#pragma once

#include <cstdint>
#include <vector>

#include "core/particles.hpp"

namespace rockcut::dem {

struct MembraneLoad {
  std::vector<std::uint32_t> particles;   ///< the outermost disc of each band, left then right
  std::vector<double> force_x_n_per_m;    ///< inward: + on the left side, - on the right
  double height_m = 0.0;                  ///< H, the specimen's height the bands divide
  double stress_pa = 0.0;                 ///< sigma_c
};

/// The membrane of confining stress `stress_pa` on the left and right sides of the specimen
/// (its bounding box); empty without discs.
MembraneLoad membrane_load(const Particles& p, double stress_pa);

}  // namespace rockcut::dem
