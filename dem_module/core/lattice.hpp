// Specimens from a regular lattice (verification scenes). The bonded random packing of the rock
// specimen lives in its own file (paper section 3.1).
#pragma once

#include "core/particles.hpp"

namespace rockcut::dem {

struct LatticeSpec {
  unsigned nx = 1, ny = 1;
  double spacing_m = 0.0;
  double radius_m = 0.0;
  double origin_x_m = 0.0, origin_y_m = 0.0;
  double density_kg_m3 = 2800.0;
};

/// nx * ny discs, row by row from the origin.
Particles make_lattice(const LatticeSpec& spec);

}  // namespace rockcut::dem
