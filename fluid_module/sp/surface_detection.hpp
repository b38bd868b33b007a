// Surface detection (paper eq. 24, section 3.3): Lucy's divergence of the position,
//   div r_i = sum_j (m_j / rho_j) (x_j - x_i) . grad_i W_ij,
// is the dimension (2) inside a body and falls towards its free surfaces. A particle at or below
// fluid.surface_div_r (the paper: 1.5) is a surface particle; sp/boundary.cpp then decides
// whether it meets free water (held at p_hydro) or a sealed side. The sum is taken in the pass
// that builds the CSPM matrices (sp/geometry.cpp), which walks the same pairs.
#pragma once

namespace rockcut::fluid::sp {

/// One pair's term of div r_i: V_j (-F_ij) r_ij^2 with (dx, dy) = x_j - x_i, since
/// grad_i W_ij = -F_ij (x_j - x_i) (sp/kernel.hpp).
[[gnu::always_inline]] inline double div_r_pair_term(double volume_j, double minus_f_ij, double dx,
                                                     double dy) {
  return volume_j * minus_f_ij * (dx * dx + dy * dy);
}

/// Whether a particle with this div r lies inside the body (not a surface particle).
inline bool inside_body(double div_r, double surface_div_r) { return div_r > surface_div_r; }

}  // namespace rockcut::fluid::sp
