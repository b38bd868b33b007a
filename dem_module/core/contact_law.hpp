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

/// Coulomb's limit on the shear spring: |F_t| <= limit (= mu F_n). Sliding cuts the spring back
/// to the limit; the cut is work done by friction [J/m], added to `friction_j`.
[[gnu::always_inline]] inline double coulomb_limited(double fs, double limit, double ks_pa, double& friction_j) {
  if (std::abs(fs) > limit) {
    friction_j += limit * (std::abs(fs) - limit) / ks_pa;
    fs = std::copysign(limit, fs);
  }
  return fs;
}

}  // namespace rockcut::dem
