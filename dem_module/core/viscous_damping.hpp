// Viscous damping: a linear dashpot beside every spring of a bond, a contact and a disc-wall (or
// disc-tool) contact, in the normal and the tangential direction (Cundall & Strack 1979; PFC's
// linear model; LAMMPS's granular hooke and BPM bond damping), per metre of thickness:
//   F_n,d = -c_n v_n,   F_t,d = -c_t v_t,   c = 2 zeta sqrt(m_eff k),
// with v_n = (v_j - v_i) . n (positive when the pair separates), v_t the shear spring's relative
// velocity of the contact points (core/incremental_shear_spring.hpp), m_eff = m_i m_j / (m_i + m_j)
// (m_i against a wall or the tool) and k the spring's stiffness (k_n or k_s). The dashpots act on
// relative motion only: a rigid translation or rotation of a chip is not damped.
// A linear spring-dashpot collision that ends when the overlap returns to zero has the normal
// coefficient of restitution e = exp(-pi zeta / sqrt(1 - zeta^2)), so zeta = -ln e / sqrt(pi^2 +
// ln^2 e) (e.g. Schwager & Poeschel 2007; exact for the linear law).
// always_inline: the step loops call these per pair.
#pragma once

#include <cmath>
#include <numbers>

namespace rockcut::dem {

/// zeta [-] of the linear spring-dashpot whose collision has restitution e in (0, 1].
inline double damping_ratio_from_restitution(double restitution) {
  const double log_e = std::log(restitution);
  return -log_e / std::sqrt(std::numbers::pi * std::numbers::pi + log_e * log_e);
}

/// e [-] of a collision under the linear spring-dashpot of damping ratio zeta in [0, 1).
inline double restitution_from_damping_ratio(double zeta) {
  return std::exp(-std::numbers::pi * zeta / std::sqrt(1.0 - zeta * zeta));
}

/// The factor on a spring's critical step sqrt(m/k) (up to its constant) that a dashpot of
/// damping ratio zeta brings: the central-difference scheme's limit 2/omega (sqrt(1 + zeta^2) -
/// zeta) (Belytschko & Hughes 1983) over the undamped 2/omega.
inline double damped_critical_step_factor(double zeta) { return std::sqrt(1.0 + zeta * zeta) - zeta; }

/// 2 zeta sqrt(k) [sqrt(Pa)], formed once per loop: c = this / sqrt(1/m_i + 1/m_j).
inline double dashpot_scale(double zeta, double stiffness_pa) { return 2.0 * zeta * std::sqrt(stiffness_pa); }

/// 1 / sqrt(1/m_i + 1/m_j) = sqrt(m_eff) [sqrt(kg/m)] of a pair (inv_mass_j = 0 for a wall).
[[gnu::always_inline]] inline double sqrt_effective_mass(double inv_mass_i, double inv_mass_j) {
  return 1.0 / std::sqrt(inv_mass_i + inv_mass_j);
}

/// A dashpot's force [N/m] (compression or along t, as the spring it sits beside) at relative
/// velocity v [m/s] with coefficient c [kg/(m s)] (what it dissipates: dashpot_dissipation).
[[gnu::always_inline]] inline double dashpot_force(double c, double velocity) { return -c * velocity; }

/// The normal and the tangential dashpot of one pair (bond, contact, disc and wall).
struct PairDashpots {
  double normal = 0.0, tangential = 0.0;  ///< [N/m], compression positive and along t
  bool any() const { return normal != 0.0 || tangential != 0.0; }
};

/// What a pair's dashpots dissipated over the drift into this evaluation [J/m]: velocity Verlet
/// moved the pair at the half-step velocities (vn, vt) under the mean of the dashpots' forces of
/// the last evaluation (`before`) and of this one (`now`), the trapezoid the ledger books every
/// other force's work with (core/energy.hpp):
///   -(F_before + F_now) / 2 . v dt.
/// Booking c v^2 dt (the second half twice) left the ledger open by a share growing with zeta.
[[gnu::always_inline]] inline double dashpot_dissipation(const PairDashpots& before,
                                                         const PairDashpots& now, double vn,
                                                         double vt, double dt) {
  return -0.5 * ((before.normal + now.normal) * vn + (before.tangential + now.tangential) * vt) *
         dt;
}

/// Both dashpots of a pair with sqrt(m_eff) `sqrt_m` at relative velocities vn, vt, their
/// coefficients dashpot_scale() x sqrt_m (ct_scale 0: no tangential dashpot, a sliding contact).
/// `before` holds the pair's dashpot forces of the last evaluation and is replaced by these; their
/// dissipation over the drift (dashpot_dissipation) is added to `dissipated_j`.
[[gnu::always_inline]] inline PairDashpots pair_dashpots(double cn_scale, double ct_scale,
                                                        double sqrt_m, double vn, double vt,
                                                        double dt, PairDashpots& before,
                                                        double& dissipated_j) {
  const double cn = cn_scale * sqrt_m, ct = ct_scale * sqrt_m;
  const PairDashpots now{dashpot_force(cn, vn), dashpot_force(ct, vt)};
  dissipated_j += dashpot_dissipation(before, now, vn, vt, dt);
  before = now;
  return now;
}

/// A pair whose dashpots stop acting in this evaluation (a contact that opens, a bond that
/// breaks): over the drift into it they acted with `before` alone, the trapezoid's other end
/// being zero. Books that and clears `before`.
[[gnu::always_inline]] inline void dashpots_released(PairDashpots& before, double vn, double vt,
                                                     double dt, double& dissipated_j) {
  dissipated_j += dashpot_dissipation(before, PairDashpots{0.0, 0.0}, vn, vt, dt);
  before = PairDashpots{0.0, 0.0};
}

}  // namespace rockcut::dem
