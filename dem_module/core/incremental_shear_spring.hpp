// The incremental shear spring (paper eq. 9's tangential force F_t and figure 4, middle; DESIGN
// section 4), the one implementation that bonds (core/bonds.cpp), contacts (core/contact_list.cpp)
// and walls (core/walls.cpp) use, per metre of thickness:
//   F_t^{n+1} = F_t^n - k_s v_t dt,
// with v_t the tangential velocity of the second body's contact point relative to the first's,
// rotation included, along t = (-n_y, n_x). Contacts and walls then cut F_t to Coulomb's limit
// (core/contact_law.hpp); a bond breaks when |F_t| exceeds its strength (core/bond_law.hpp).
// Inline: the step loops call these per pair, with the floating-point operations in the order
// they always had (the bit-identity and regression tests hold them to it).
// always_inline: with plain inline GCC 12 compiled the step loops differently (less vectorised).
#pragma once

namespace rockcut::dem {

/// v_t [m/s]: the relative velocity (dvx, dvy) of the second body against the first, along
/// t = (-ny, nx) for the unit normal (nx, ny), less the contact points' spin speeds w_i r_i and
/// w_j r_j (0 for a wall).
[[gnu::always_inline]] inline double shear_spring_velocity(double dvx, double dvy, double nx,
                                                           double ny, double spin_i,
                                                           double spin_j) {
  return -dvx * ny + dvy * nx - spin_i - spin_j;
}

/// F_t after dt [N/m]: the spring's force less k_s v_t dt (k_s [Pa], v_t [m/s], dt [s]).
[[gnu::always_inline]] inline double shear_spring_update(double force, double ks_pa, double vt, double dt) {
  return force - ks_pa * vt * dt;
}

/// The same update with k_s dt formed once outside the loop (the bonds'): it rounds differently
/// from shear_spring_update(), and each caller keeps the form its stored results were made with.
[[gnu::always_inline]] inline double shear_spring_update_hoisted(double force, double ks_dt, double vt) {
  return force - ks_dt * vt;
}

}  // namespace rockcut::dem
