// Miedema's criterion for the failure mode: does the rock ahead of the tool fail in tension before
// the flow type's shear plane fails in shear?
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
//   sigma_min < -sigma_t               "tensile": the circle reaches the tension cut-off before the
//                                      shear plane fails: tensile failure, the tear type (Miedema's
//                                      upper limit in figures 8-53, 8-54)
//   -sigma_t <= sigma_min              "shear": the shear plane fails first (Miedema's chip, shear
//                                      and flow types; his lower limit, where the chip type gives
//                                      way to pure shear, is not computed here)
//   alpha + delta + phi >= 180 deg     "none": no shear plane (stresses NaN)
// Miedema's worked numbers (section 8.9 and exercise 16.8.5 of the 2019a edition): UCS 100 MPa,
// phi 20, alpha 60 deg gives sigma_min -8.48 MPa, "the transition tensile failure/shear failure at
// a tensile strength of about -8.5 MPa"; UCS 60 MPa, BTS 3 MPa gives -5.09 MPa, tensile failure.
// He plots the limit as -BTS/c against alpha (figure 8-53) and as UCS/BTS (figure 8-54, with
// c = UCS (1 - sin phi) / (2 cos phi), eq. 3-34).
#pragma once

#include <string>

namespace rockcut::coupler::cutting_models {

struct FailureMode {
  double shear_plane_normal_stress_pa = 0.0;  ///< sigma_n, compression positive
  double least_principal_stress_pa = 0.0;     ///< sigma_min, compression positive
  std::string mode;                           ///< "tensile", "shear" or "none"
};

FailureMode miedema_failure_mode(double cohesion_pa, double friction_angle_deg,
                                 double tensile_strength_pa, double tool_friction_angle_deg,
                                 double blade_angle_deg);

}  // namespace rockcut::coupler::cutting_models
