// The bond law (paper section 3.1, eq. 9 and figure 4; DESIGN section 4), per metre of thickness:
// linear elastic and perfectly brittle (or softening past its strength, core/bond_softening.hpp).
// Normal force k_n (L0 - L), compression positive, in tension and compression; tangential force
// from the incremental shear spring (core/incremental_shear_spring.hpp). A bond breaks in tension
// when the tensile force exceeds T_n, in shear when |F_t| > T_s, never in compression; after
// breaking the pair may collide.
// always_inline: with plain inline GCC 12 compiled the step loops differently (less vectorised).
#pragma once

#include <algorithm>
#include <cmath>

namespace rockcut::dem {

struct BondLaw {
  double normal_stiffness_pa = 0.0;       ///< K_n [Pa] (N/m per metre of thickness)
  double shear_stiffness_pa = 0.0;        ///< K_s [Pa] (N/m per metre of thickness)
  double tensile_strength_n_per_m = 0.0;  ///< T_n [N per metre of thickness]
  double shear_strength_n_per_m = 0.0;    ///< T_s [N per metre of thickness]
  /// tan(phi_b): the shear strength's growth with the bond's compression (0: the paper's bond).
  double friction_coefficient = 0.0;
  /// lambda: the softening span over the elastic span (core/bond_softening.hpp); 0: the paper's
  /// perfectly brittle bond.
  double softening_ratio = 0.0;
};

/// How a bond broke.
enum class BreakMode { tensile = 0, shear = 1 };

struct BondBreak {
  BreakMode mode;
  double time_s;
  double x_m, y_m;  ///< bond midpoint
  unsigned i, j;
};

/// F_n [N/m] of a bond of rest length L0 at length L [m], compression positive.
[[gnu::always_inline]] inline double bond_normal_force(double kn_pa, double rest_length_m, double length_m) {
  return kn_pa * (rest_length_m - length_m);
}

/// The shear strength of a bond carrying F_n (compression positive): T_s + tan(phi_b) max(F_n, 0),
/// a Mohr-Coulomb bond as PFC's parallel bond with a friction angle (Itasca, linearpbond pb_fa).
/// The paper's bond (figure 4) is tan(phi_b) = 0: its shear strength does not grow under
/// compression, which leaves the bonded rock's peak envelope flat (docs/calibration.md, "The
/// Mohr-Coulomb envelope"). With tan(phi_b) = 0 this returns T_s bit for bit.
[[gnu::always_inline]] inline double bond_shear_strength(double ts, double tan_phi_b, double fn) {
  return ts + tan_phi_b * std::max(fn, 0.0);
}

/// Figure 4: exceeding a strength breaks the bond (tension: F_n < -T_n; shear: |F_t| > T_s, with
/// T_s from bond_shear_strength).
[[gnu::always_inline]] inline bool bond_breaks(double fn, double fs, double tn, double ts) {
  return fn < -tn || fs > ts || fs < -ts;
}

/// The mode of a break: the strength exceeded by the larger ratio.
[[gnu::always_inline]] inline BreakMode bond_break_mode(double fn, double fs, double tn, double ts) {
  const double tension_ratio = -fn / tn, shear_ratio = std::abs(fs) / ts;
  return tension_ratio >= shear_ratio ? BreakMode::tensile : BreakMode::shear;
}

/// Elastic energy [J/m] of a bond carrying F_n and F_t.
[[gnu::always_inline]] inline double bond_energy(double fn, double fs, double kn_pa, double ks_pa) {
  return 0.5 * fn * fn / kn_pa + 0.5 * fs * fs / ks_pa;
}

/// The energy [J/m] a bond releases as it breaks over the drift into the evaluation that breaks
/// it: its springs held F_before at the last evaluation and would hold F_now at this one, and
/// carry nothing from it on, except that a pair pressed together takes the contact's normal
/// force fc (stiffness kc). What velocity Verlet's kick (the trapezoid of the forces at both ends
/// over the drift) and the springs' energy change leave unaccounted:
///   normal: (F_b^2 - (F_b + fc)(F_b - F_now)) / (2 k_n) - fc^2 / (2 k_c),   shear: F_b F_now / (2 k_s).
/// With fc = 0 it is F_b F_now / (2 k), between the bond's energy before and at the break.
/// Booking the energy at the break (F_now^2 / 2k) left the ledger open by the kick's half step.
[[gnu::always_inline]] inline double bond_energy_released(double fn_before, double fn_now,
                                                          double fc, double fs_before,
                                                          double fs_now, double kn_pa,
                                                          double ks_pa, double kc_pa) {
  const double normal =
      (fn_before * fn_before - (fn_before + fc) * (fn_before - fn_now)) / (2.0 * kn_pa) -
      (fc > 0.0 ? 0.5 * fc * fc / kc_pa : 0.0);
  return normal + 0.5 * fs_before * fs_now / ks_pa;
}

}  // namespace rockcut::dem
