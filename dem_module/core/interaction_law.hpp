// The pair laws of DESIGN section 4, per metre of thickness:
//  - contact: normal k_n * overlap (compression only), tangential incremental k_s * du_t limited by
//    Coulomb mu * F_n;
//  - bond (linear elastic, perfectly brittle, paper section 3.1 and figure 4): normal
//    k_n (L0 - L) in tension and compression, tangential incremental k_s * du_t; breaks in tension
//    when the tensile force exceeds T_n, in shear when |F_t| > T_s, never in compression.
#pragma once

namespace rockcut::dem {

struct ContactLaw {
  double normal_stiffness_n_m = 0.0;  ///< k_n [N/m per m]
  double shear_stiffness_n_m = 0.0;   ///< k_s [N/m per m]
  double friction = 0.0;              ///< mu [-]
};

struct BondLaw {
  double normal_stiffness_n_m = 0.0;   ///< K_n [N/m per m]
  double shear_stiffness_n_m = 0.0;    ///< K_s [N/m per m]
  double tensile_strength_n = 0.0;     ///< T_n [N per m]
  double shear_strength_n = 0.0;       ///< T_s [N per m]
};

/// How a bond broke.
enum class BreakMode { tensile = 0, shear = 1 };

struct BondBreak {
  BreakMode mode;
  double time_s;
  double x_m, y_m;  ///< bond midpoint
  unsigned i, j;
};

}  // namespace rockcut::dem
