#include "cutting_models/nishimatsu_shear_plane.hpp"

#include <cmath>

namespace rockcut::coupler::cutting_models {

double nishimatsu_exponent_fit(double rake_angle_deg) { return 11.3 - 0.18 * rake_angle_deg; }

CuttingForce nishimatsu_shear_plane(double cohesion_pa, double friction_angle_deg,
                                    double tool_friction_angle_deg, double blade_angle_deg,
                                    double cut_depth_m, double stress_exponent) {
  const double phi = radians(friction_angle_deg), delta = radians(tool_friction_angle_deg),
               rake = radians(rake_angle_deg(blade_angle_deg));
  CuttingForce f;
  f.horizontal_n_per_m = 2.0 * cohesion_pa * cut_depth_m * std::cos(phi) * std::cos(delta - rake) /
                         ((stress_exponent + 1.0) * (1.0 - std::sin(phi + delta - rake)));
  // The thrust F_t pushes the tool up (out of the rock) when delta > alpha_r.
  f.vertical_up_n_per_m = f.horizontal_n_per_m * std::tan(delta - rake);
  return f;
}

}  // namespace rockcut::coupler::cutting_models
