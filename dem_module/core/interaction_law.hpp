// What every pair law shares (paper eq. 9; DESIGN section 4): the interaction force is
// F = n F_n + t F_t, with n the unit normal from the first body to the second and t = (-n_y, n_x).
// The laws themselves, one file each: core/contact_law.hpp (contacts, walls and the tool),
// core/bond_law.hpp (bonds), and the tangential spring they share,
// core/incremental_shear_spring.hpp.
#pragma once

#include "core/bond_law.hpp"
#include "core/contact_law.hpp"
#include "core/incremental_shear_spring.hpp"

namespace rockcut::dem {

/// Eq. 9: the force (fx, fy) on the second body of normal force fn (compression positive) and
/// tangential force fs along t = (tx, ty) = (-ny, nx).
struct PairForce {
  double fx, fy;
};
[[gnu::always_inline]] inline PairForce pair_force(double fn, double fs, double nx, double ny, double tx, double ty) {
  return {fn * nx + fs * tx, fn * ny + fs * ty};
}

}  // namespace rockcut::dem
