// Merchant's / Miedema's flow type: the rock shears along one plane from the tool tip to the free
// surface, and the shear angle is the one that needs the least force.
//
// Miedema (2014), "The Delft Sand, Clay & Rock Cutting Model", chapter 3 (the general cutting
// process): the layer's equilibrium of the cohesive force C on the shear plane, the grain forces
// K1 (internal friction phi) and K2 (rock-tool friction delta), and the pore under-pressure forces
// W1 (shear plane) and W2 (blade), in Miedema's notation (chapter 3, "The equilibrium of forces"):
//
//   K2  = [W2 sin(alpha+beta+phi) + W1 sin(phi) + C cos(phi)] / sin(alpha+beta+delta+phi)
//   F_h = K2 sin(alpha+delta) - W2 sin(alpha)          horizontal force on the tool
//   F_v = K2 cos(alpha+delta) - W2 cos(alpha)          (Miedema: positive pushes the tool down)
//   C = c h / sin(beta),  W1 = dp h / sin(beta),  W2 = dp h_b / sin(alpha)
//
// With no pore under-pressure (dp = 0: dry or drained rock) the minimum over beta is closed form
// (Miedema 2014 eq. 3-33; Merchant 1945 with phi = 0):
//
//   beta = (pi - alpha - delta - phi) / 2
//   F_h  = 2 c h cos(phi) sin(alpha+delta) / (1 + cos(alpha+delta+phi))
//
//   c      cohesion [Pa];  phi internal friction angle;  delta rock-tool friction angle
//   alpha  blade angle (cutting_force.hpp);  h cut depth [m];  h_b blade height [m]
//   dp     pore under-pressure (below the ambient pressure) on the shear plane and the blade [Pa]
//
// No gravity, inertia or adhesion (negligible for rock: Miedema 2014 section 8.1). The flow type
// exists for alpha + delta + phi < 180 deg; beyond, the functions return NaN.
#pragma once

#include "cutting_models/cutting_force.hpp"

namespace rockcut::coupler::cutting_models {

struct FlowTypeForce {
  CuttingForce force;
  double shear_angle_deg = 0.0;  ///< beta, the shear plane against the cutting direction
};

/// The minimum-force shear angle without pore under-pressure, beta = (180 - alpha - delta - phi) / 2
/// [deg]; NaN where alpha + delta + phi >= 180 deg (no shear plane).
double merchant_shear_angle_deg(double friction_angle_deg, double tool_friction_angle_deg,
                                double blade_angle_deg);

/// Dry / drained flow type at the minimum-force shear angle (closed form, dp = 0).
FlowTypeForce merchant_flow_type(double cohesion_pa, double friction_angle_deg,
                                 double tool_friction_angle_deg, double blade_angle_deg,
                                 double cut_depth_m);

/// The flow type's force at a given shear angle with pore under-pressure `under_pressure_pa` on
/// the shear plane and on the blade (height `blade_height_m`): the equilibrium above.
CuttingForce flow_type_at_shear_angle(double cohesion_pa, double friction_angle_deg,
                                      double tool_friction_angle_deg, double blade_angle_deg,
                                      double cut_depth_m, double blade_height_m,
                                      double under_pressure_pa, double shear_angle_deg);

}  // namespace rockcut::coupler::cutting_models
