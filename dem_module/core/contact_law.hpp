// The contact law between unbonded discs and between a disc and a wall or the tool (paper section
// 3.1, eq. 9: F = n F_n + t F_t; DESIGN section 4), per metre of thickness: normal force
// k_n * overlap, compression only; tangential force from the incremental shear spring
// (core/incremental_shear_spring.hpp), limited by Coulomb, |F_t| <= mu F_n (static or dynamic
// friction: sliding cuts the spring back to the limit).
// always_inline: with plain inline GCC 12 compiled the step loops differently (less vectorised).
#pragma once

#include <cmath>
#include <type_traits>

namespace rockcut::dem {

struct ContactLaw {
  double normal_stiffness_pa = 0.0;  ///< k_n [Pa] (N/m per metre of thickness)
  double shear_stiffness_pa = 0.0;   ///< k_s [Pa] (N/m per metre of thickness)
  double friction = 0.0;             ///< mu [-]
  /// zeta [-] of the dashpots beside the springs (core/viscous_damping.hpp), the bonds' too (the
  /// DEM passes it to BondSet::compute); 0: none.
  double damping_ratio = 0.0;
  /// mu_r [-] of the rolling spring (core/rolling_resistance.hpp); 0: none.
  double rolling_friction = 0.0;
};

/// Calls f(dashpots, rolling) with std::bool_constant arguments for the law's dashpots
/// (damping_ratio > 0) and rolling springs (rolling_friction > 0): the pair loops are compiled once
/// per combination, so none tests them per pair, and one without either is the plain loop.
template <class F>
void with_pair_laws(const ContactLaw& law, F&& f) {
  const bool dashpots = law.damping_ratio > 0.0, rolling = law.rolling_friction > 0.0;
  if (dashpots && rolling) {
    f(std::true_type{}, std::true_type{});
  } else if (dashpots) {
    f(std::true_type{}, std::false_type{});
  } else if (rolling) {
    f(std::false_type{}, std::true_type{});
  } else {
    f(std::false_type{}, std::false_type{});
  }
}

/// F_n [N/m] of a contact with overlap > 0 [m], compression positive.
[[gnu::always_inline]] inline double contact_normal_force(double kn_pa, double overlap_m) { return kn_pa * overlap_m; }

/// Coulomb's limit on the shear spring: |F_t| <= limit (= mu F_n). Sliding cuts the spring from
/// `trial` (`before` less k_s v_t dt) back to the limit; what the step lost is work done by
/// friction [J/m], added to `friction_j`:
///   (F_before + F_after) (trial - F_after) / (2 k_s),
/// the work velocity Verlet's kick did against the spring (the trapezoid of F_before and F_after
/// over the slip, as the ledger books every force) less the spring's energy change. In steady
/// sliding (F_before = F_after = the limit) it is the limit times the slip; where the limit falls
/// within a step (a contact opening, its normal force dropping) it is more, and booking the limit
/// times the slip alone left 5-7 % of an undamped cut's work on no line.
[[gnu::always_inline]] inline double coulomb_limited(double before, double trial, double limit,
                                                     double ks_pa, double& friction_j) {
  if (std::abs(trial) > limit) {
    const double after = std::copysign(limit, trial);
    friction_j += 0.5 * (before + after) * (trial - after) / ks_pa;
    return after;
  }
  return trial;
}

/// A contact that opens: its normal force, and with it the Coulomb limit, fell to zero within
/// the drift, and the shear spring `fs` slid off. coulomb_limited with F_after = 0 books it as
/// friction's (`vt_dt`: the tangential motion over the drift, v_t dt) and clears the spring.
[[gnu::always_inline]] inline void release_on_opening(double& fs, double ks_pa, double vt_dt,
                                                      double& friction_j) {
  friction_j += 0.5 * fs * (fs - ks_pa * vt_dt) / ks_pa;
  fs = 0.0;
}

}  // namespace rockcut::dem
