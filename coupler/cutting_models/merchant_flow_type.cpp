#include "cutting_models/merchant_flow_type.hpp"

#include <cmath>
#include <limits>

namespace rockcut::coupler::cutting_models {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

double merchant_shear_angle_deg(double friction_angle_deg, double tool_friction_angle_deg,
                                double blade_angle_deg) {
  const double rest_deg = 180.0 - blade_angle_deg - tool_friction_angle_deg - friction_angle_deg;
  return rest_deg > 0.0 ? 0.5 * rest_deg : kNaN;
}

FlowTypeForce merchant_flow_type(double cohesion_pa, double friction_angle_deg,
                                 double tool_friction_angle_deg, double blade_angle_deg,
                                 double cut_depth_m) {
  FlowTypeForce r;
  r.shear_angle_deg =
      merchant_shear_angle_deg(friction_angle_deg, tool_friction_angle_deg, blade_angle_deg);
  if (std::isnan(r.shear_angle_deg)) {
    r.force = {kNaN, kNaN};
    return r;
  }
  r.force = flow_type_at_shear_angle(cohesion_pa, friction_angle_deg, tool_friction_angle_deg,
                                     blade_angle_deg, cut_depth_m, 0.0, 0.0, r.shear_angle_deg);
  return r;
}

CuttingForce flow_type_at_shear_angle(double cohesion_pa, double friction_angle_deg,
                                      double tool_friction_angle_deg, double blade_angle_deg,
                                      double cut_depth_m, double blade_height_m,
                                      double under_pressure_pa, double shear_angle_deg) {
  const double a = radians(blade_angle_deg), phi = radians(friction_angle_deg),
               delta = radians(tool_friction_angle_deg), beta = radians(shear_angle_deg);
  const double denominator = std::sin(a + beta + delta + phi);
  if (beta <= 0.0 || denominator <= 0.0) return {kNaN, kNaN};
  const double c_force = cohesion_pa * cut_depth_m / std::sin(beta);
  const double w1 = under_pressure_pa * cut_depth_m / std::sin(beta);
  const double w2 = under_pressure_pa * blade_height_m / std::sin(a);
  const double k2 = (w2 * std::sin(a + beta + phi) + w1 * std::sin(phi) + c_force * std::cos(phi)) /
                    denominator;
  CuttingForce f;
  f.horizontal_n_per_m = k2 * std::sin(a + delta) - w2 * std::sin(a);
  // Miedema's F_v pushes the tool down when positive; the rock's force on the tool, up, is -F_v.
  f.vertical_up_n_per_m = -(k2 * std::cos(a + delta) - w2 * std::cos(a));
  return f;
}

}  // namespace rockcut::coupler::cutting_models
