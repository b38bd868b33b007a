// Darcy's law (paper eq. 12), q = -(kappa / mu) grad p, in the storage equation (eqs. 13-14) with a
// uniform permeability: the pore pressure diffuses with D = M kappa / mu (the coupler's Peclet
// number, coupler/observers/peclet.cpp, uses the same D).
#pragma once

namespace rockcut::fluid::sp {

/// D = M kappa / mu [m^2/s] from the bulk modulus M [Pa], the intrinsic permeability kappa [m^2]
/// and the pore fluid's viscosity mu [Pa s].
inline double darcy_diffusivity_m2_s(double bulk_modulus_pa, double permeability_m2,
                                     double viscosity_pa_s) {
  return bulk_modulus_pa * permeability_m2 / viscosity_pa_s;
}

}  // namespace rockcut::fluid::sp
