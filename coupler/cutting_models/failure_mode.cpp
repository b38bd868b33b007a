#include "cutting_models/failure_mode.hpp"

#include <cmath>

#include "cutting_models/cutting_force.hpp"
#include "cutting_models/merchant_flow_type.hpp"

namespace rockcut::coupler::cutting_models {

FailureMode miedema_failure_mode(double cohesion_pa, double friction_angle_deg,
                                 double tensile_strength_pa, double tool_friction_angle_deg,
                                 double blade_angle_deg) {
  const double a = radians(blade_angle_deg), phi = radians(friction_angle_deg),
               delta = radians(tool_friction_angle_deg);
  const double beta_deg =
      merchant_shear_angle_deg(friction_angle_deg, tool_friction_angle_deg, blade_angle_deg);
  const double beta = radians(beta_deg);
  FailureMode m;
  if (std::isnan(beta_deg)) {
    m.shear_plane_normal_stress_pa = m.least_principal_stress_pa = std::nan("");
    m.mode = "none";
    return m;
  }
  m.shear_plane_normal_stress_pa =
      -cohesion_pa * std::cos(a + beta + delta) * std::cos(phi) / std::sin(a + beta + delta + phi);
  const double tau = cohesion_pa + m.shear_plane_normal_stress_pa * std::tan(phi);
  m.least_principal_stress_pa =
      m.shear_plane_normal_stress_pa + tau * (std::sin(phi) - 1.0) / std::cos(phi);
  // sigma_min <= sigma_n: a shear plane itself in tension beyond the BTS is a case of the first.
  m.mode = m.least_principal_stress_pa < -tensile_strength_pa ? "tensile" : "shear";
  return m;
}

}  // namespace rockcut::coupler::cutting_models
