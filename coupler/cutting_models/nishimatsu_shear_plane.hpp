// Nishimatsu's shear plane: Merchant's single shear plane with a stress that falls from the tool
// tip to the free surface as (1 - x/L)^n, the rock obeying Mohr-Coulomb.
//
// Nishimatsu, Y. (1972) "The mechanics of rock cutting", Int. J. Rock Mech. Min. Sci. 9:261-270;
// as presented by Miedema (2014) section 8.3 ("The Nishimatsu model"):
//
//   F_c = 2 c d cos(phi) cos(delta - alpha_r) / [(n + 1) (1 - sin(phi + delta - alpha_r))]
//   F_t = F_c tan(delta - alpha_r)       the thrust, pushing the tool out of the rock
//
//   c        cohesion (shear strength at zero normal stress) [Pa]
//   phi      internal friction angle;  delta rock-tool friction angle
//   alpha_r  rake angle = 90 deg - alpha (cutting_force.hpp);  d cut depth [m]
//   n        stress distribution exponent [-]; Nishimatsu's fit to his tests: n = 11.3 - 0.18 alpha_r
//            (alpha_r in degrees)
//
// With n = 0 (uniform stress on the shear plane) F_c is Merchant's minimum force: substituting
// alpha_r = 90 - alpha gives 2 c d cos(phi) sin(alpha+delta) / (1 + cos(alpha+delta+phi)), the
// flow type's closed form (merchant_flow_type.hpp). A peak force, like Evans'.
#pragma once

#include "cutting_models/cutting_force.hpp"

namespace rockcut::coupler::cutting_models {

/// Nishimatsu's fit of the exponent to the rake angle: n = 11.3 - 0.18 alpha_r [deg].
double nishimatsu_exponent_fit(double rake_angle_deg);

CuttingForce nishimatsu_shear_plane(double cohesion_pa, double friction_angle_deg,
                                    double tool_friction_angle_deg, double blade_angle_deg,
                                    double cut_depth_m, double stress_exponent);

}  // namespace rockcut::coupler::cutting_models
