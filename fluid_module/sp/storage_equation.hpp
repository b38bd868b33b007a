// The storage equation of the pore pressure (paper eqs. 13-14; DESIGN section 4): with
// p = M (zeta - alpha eps_v) (eq. 13) and Darcy's flux u = -(kappa / mu) grad p (eq. 12),
//   dp/dt = D lap p - alpha M d(eps_v)/dt,   D = M kappa / mu   (eq. 14, uniform kappa),
// where lap is the SP Laplacian of eq. 20 (sp/operators.hpp) and d(eps_v)/dt the corrected
// divergence of eq. 17. The explicit model advances it by forward Euler (models/explicit_model.cpp),
// the implicit model by backward Euler (sp/implicit_system.cpp).
#pragma once

namespace rockcut::fluid::sp {

/// The source term of eq. 14 [Pa/s]: -alpha M d(eps_v)/dt, with alpha_m = alpha M [Pa] and the
/// volumetric strain rate [1/s].
inline double storage_source(double alpha_m_pa, double strain_rate_per_s) {
  return -alpha_m_pa * strain_rate_per_s;
}

/// dp/dt of eq. 14 [Pa/s] from the Laplacian of p [Pa/m^2] and the source [Pa/s].
inline double storage_rate(double diffusivity_m2_s, double laplacian_pa_m2, double source_pa_s) {
  return diffusivity_m2_s * laplacian_pa_m2 + source_pa_s;
}

}  // namespace rockcut::fluid::sp
