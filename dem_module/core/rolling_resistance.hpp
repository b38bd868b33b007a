// Rolling resistance: an elastic-plastic rolling spring on every unbonded contact and disc-wall
// (or disc-tool) contact (Iwashita & Oda 1998; Ai, Chen, Rotter & Ooi 2011, model type C without
// its dashpot, as LIGGGHTS's "epsd2"), per metre of thickness:
//   M_r^{n+1} = M_r^n - k_r (w_i - w_j) dt,   |M_r| <= mu_r R_r F_n,   k_r = k_s R_r^2,
// with R_r = r_i r_j / (r_i + r_j) (r_i against a wall, which does not spin), M_r the moment on
// disc i (-M_r on j) and F_n the normal spring's force. It resists relative rolling, the motion
// a contact's shear spring cannot see (grains rolling over each other and up the rake face), and
// leaves a rigid rotation (w_i = w_j) alone. Where the moment is cut back to the limit, the cut
// is dissipated and booked as Coulomb friction's is (core/contact_law.hpp); the spring stores
// M_r^2 / (2 k_r).
// always_inline: the step loops call these per pair.
#pragma once

#include <cmath>

namespace rockcut::dem {

/// R_r [m] of two discs (r_j = 0 is not allowed; a wall passes r_j = infinity: use r_i).
[[gnu::always_inline]] inline double rolling_radius(double r_i, double r_j) { return r_i * r_j / (r_i + r_j); }

/// The rolling spring's moment on disc i [N m/m] after dt, cut to mu_r R_r F_n; the cut's work
/// [J/m] is added to `dissipated_j`. w_rel = w_i - w_j [rad/s], kr = k_s R_r^2 [N m/m per rad].
[[gnu::always_inline]] inline double rolling_moment_update(double moment, double kr, double w_rel,
                                                           double dt, double limit,
                                                           double& dissipated_j) {
  double m = moment - kr * w_rel * dt;
  if (std::abs(m) > limit) {
    // As coulomb_limited (core/contact_law.hpp): the kick's trapezoid less the spring's change.
    const double after = std::copysign(limit, m);
    dissipated_j += 0.5 * (moment + after) * (m - after) / kr;
    m = after;
  }
  return m;
}

/// A contact that opens: the rolling spring slides off as its limit falls to zero (as
/// release_on_opening, core/contact_law.hpp); books it and clears `moment`.
[[gnu::always_inline]] inline void rolling_released(double& moment, double kr, double w_rel,
                                                    double dt, double& dissipated_j) {
  dissipated_j += 0.5 * moment * (moment - kr * w_rel * dt) / kr;
  moment = 0.0;
}

/// Elastic energy [J/m] of a rolling spring of stiffness kr carrying `moment`.
[[gnu::always_inline]] inline double rolling_energy(double moment, double kr) { return 0.5 * moment * moment / kr; }

}  // namespace rockcut::dem
