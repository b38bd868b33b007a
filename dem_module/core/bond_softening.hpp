// A softening bond: the paper's bond (core/bond_law.hpp, figure 4) with a linear softening branch
// after its strength, as Hillerborg's fictitious crack (Hillerborg, Modeer & Petersson 1976) and
// the soft-bond model of PFC (Itasca): past its strength a bond does not break at once but gives
// way over a softening span, and the energy it takes to break grows with that span.
//
// One damage D in [0, 1] per bond, growing only, shared by both modes:
//   tension:  opening delta = L - L0 > 0. The envelope rises as k_n delta to T_n at
//             delta_p = T_n / k_n, then falls linearly to zero at delta_u = delta_p (1 + lambda):
//             on it D = (delta / delta_p - 1) / lambda and T = T_n (1 - D). Below the envelope
//             the bond unloads and reloads along its secant, T = k_sec delta with
//             k_sec = k_n (1 - D) / (1 + lambda D) (damage mechanics' secant unloading).
//             In compression the crack closes: k_n, whatever D.
//   shear:    the incremental shear spring k_s, limited to (T_s + tan(phi_b) F_n+) (1 - D); the
//             plastic slip past the limit, (|F_trial| - limit) / k_s, grows D by that slip over
//             (1 + lambda) T_s / k_s, so that, slid at a constant rate, the shear force falls from
//             T_s to zero over lambda times its elastic slip T_s / k_s (the spring's own recoil is
//             the other T_s / k_s of plastic slip), and breaking takes (1 + lambda) T_s^2 / 2k_s.
// A bond whose D reaches 1 breaks. lambda = softening_ratio; 0 is the paper's brittle bond.
// The work to break a bond in pure tension is the area under its envelope,
//   G_b = T_n delta_u / 2 = (1 + lambda) T_n^2 / (2 k_n)   [J/m],
// 1 + lambda times the brittle bond's.
#pragma once

#include <algorithm>
#include <cmath>

namespace rockcut::dem {

/// k_sec / k_n of a bond at damage D: its tensile stiffness along the secant.
[[gnu::always_inline]] inline double secant_fraction(double damage, double softening_ratio) {
  return (1.0 - damage) / (1.0 + softening_ratio * damage);
}

/// The damage on the tensile envelope at opening delta [m] (delta_p = T_n / k_n), clipped to
/// [0, 1].
[[gnu::always_inline]] inline double tensile_envelope_damage(double opening_m, double peak_opening_m,
                                                             double softening_ratio) {
  return std::clamp((opening_m / peak_opening_m - 1.0) / softening_ratio, 0.0, 1.0);
}

/// The bond's normal force [N/m], tension positive, at opening delta [m] and damage D: the secant
/// in tension, k_n in compression.
[[gnu::always_inline]] inline double softened_tension(double kn_pa, double opening_m, double damage,
                                                      double softening_ratio) {
  return opening_m > 0.0 ? kn_pa * secant_fraction(damage, softening_ratio) * opening_m
                         : kn_pa * opening_m;
}

/// The normal spring's stored energy [J/m] at opening delta and damage D (1/2 k delta^2 with the
/// stiffness of softened_tension).
[[gnu::always_inline]] inline double softened_normal_energy(double kn_pa, double opening_m,
                                                            double damage, double softening_ratio) {
  return 0.5 * softened_tension(kn_pa, opening_m, damage, softening_ratio) * opening_m;
}

/// G_b: the work [J/m] to break a bond in pure tension, the area under its envelope.
inline double tensile_fracture_work(double kn_pa, double tn_n_per_m, double softening_ratio) {
  return 0.5 * (1.0 + softening_ratio) * tn_n_per_m * tn_n_per_m / kn_pa;
}

}  // namespace rockcut::dem
