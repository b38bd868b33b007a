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
  /// Square: rows spacing_m apart. Hexagonal (triangular): rows spacing_m * sqrt(3)/2 apart, odd
  /// rows shifted by spacing_m / 2, so that every interior disc has six neighbours at spacing_m.
  bool hexagonal = false;
};

/// nx * ny discs, row by row from the origin.
Particles make_lattice(const LatticeSpec& spec);

}  // namespace rockcut::dem
