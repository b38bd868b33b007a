// Miedema's criterion for the failure mode: does the rock fail in tension (tear / chip type) or in
// shear (shear / flow type) ahead of the tool?
//
// Miedema (2014) section 8.7 ("Tensile failure or shear failure", figures 8-53 and 8-54): take the
// flow type's shear plane at its minimum-force angle beta (merchant_flow_type.hpp). Its normal
// stress sigma_n and shear stress tau = c + sigma_n tan(phi) (compression positive) lie on the
// Mohr-Coulomb envelope; the Mohr circle tangent to the envelope there has centre
// sigma_c = sigma_n + tau tan(phi), radius R = tau / cos(phi) and least principal stress
// sigma_min = sigma_c - R. With the layer's equilibrium (no pore pressure):
//
//   sigma_n / c = -cos(alpha+beta+delta) cos(phi) / sin(alpha+beta+delta+phi)
//   sigma_min   = sigma_n + tau (sin(phi) - 1) / cos(phi)
//
// Compared with the tensile strength sigma_t (BTS):
//   sigma_n < -sigma_t                 "tensile": the shear plane itself is in tension beyond the
//                                      BTS (Miedema's upper limit; the tear type)
//   sigma_min < -sigma_t <= sigma_n    "tensile_and_shear": the circle reaches the tension cut-off
//                                      before shear failure completes (the chip type)
//   -sigma_t <= sigma_min              "shear": shear failure only (the shear / flow type)
//   alpha + delta + phi >= 180 deg     "none": no shear plane (stresses NaN)
// Miedema plots the limits as -BTS/c against alpha (figure 8-53) and as UCS/BTS (figure 8-54,
// with c = UCS (1 - sin phi) / (2 cos phi), eq. 3-34).
#pragma once

#include <string>

namespace rockcut::coupler::cutting_models {

struct FailureMode {
  double shear_plane_normal_stress_pa = 0.0;  ///< sigma_n, compression positive
  double least_principal_stress_pa = 0.0;     ///< sigma_min, compression positive
  std::string mode;                           ///< "tensile", "tensile_and_shear", "shear" or "none"
};

FailureMode miedema_failure_mode(double cohesion_pa, double friction_angle_deg,
                                 double tensile_strength_pa, double tool_friction_angle_deg,
                                 double blade_angle_deg);

}  // namespace rockcut::coupler::cutting_models
