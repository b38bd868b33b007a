// Small specimens for DEM unit tests.
#pragma once

#include <cmath>

#include "core/bonds.hpp"
#include "core/cell_grid.hpp"
#include "core/dem_system.hpp"
#include "core/lattice.hpp"
#include "core/particles.hpp"

namespace rockcut::dem::test {

/// Two discs of radius 1 mm, 10 mm apart along x: free of each other, for tests of the
/// integrator and of external forces.
inline Particles two_discs() {
  LatticeSpec spec;
  spec.nx = 2;
  spec.ny = 1;
  spec.spacing_m = 0.01;
  spec.radius_m = 0.001;
  return make_lattice(spec);
}

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

/// Two bonded discs of radius 0.3 mm touching along x; disc 1 is driven at (vx, vy). Both get a
/// mass of 1e30 kg/m, so the bond force (<= 1e5 N/m) changes their velocities by less than
/// 1e-35 m/s per step.
inline DemSystem driven_pair(double vx, double vy, const BondLaw& law) {
  Particles p;
  const double r = 3e-4;
  p.add(0.0, 0.0, r, 2800);
  p.add(2 * r, 0.0, r, 2800);
  for (auto* inv : {&p.inv_mass, &p.inv_inertia}) (*inv)[0] = (*inv)[1] = 1e-30;
  p.velocity = {0.0, 0.0, vx, vy};
  BondSet bonds = bond_all_touching(p, law);
  DemSettings s;
  s.contact = {law.normal_stiffness_pa, law.shear_stiffness_pa, 1.0};
  return DemSystem(std::move(p), s, std::move(bonds));
}

}  // namespace rockcut::dem::test
