// Small specimens for DEM unit tests.
#pragma once

#include <cmath>

#include "core/bonds.hpp"
#include "core/cell_grid.hpp"
#include "core/particles.hpp"

namespace rockcut::dem::test {

/// Equal touching discs on a hexagonal lattice, rows along x.
inline Particles hex_block(int nx, int ny, double r, double rho = 2800) {
  Particles p;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      p.add((2 * i + (j % 2)) * r, j * std::sqrt(3.0) * r, r, rho);
    }
  }
  return p;
}

/// Table 1 as printed (K_n 10 GPa, K_s 25 GPa, T_n 10 kN/m, T_s 20 kN/m).
inline BondLaw table1_bond() { return {1e10, 2.5e10, 1e4, 2e4}; }

inline BondSet bond_all_touching(const Particles& p, const BondLaw& law) {
  CellGrid grid;
  return BondSet::install(p, law, 1e-9, grid);
}

}  // namespace rockcut::dem::test
