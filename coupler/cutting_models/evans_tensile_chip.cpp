#include "cutting_models/evans_tensile_chip.hpp"

#include <cmath>

namespace rockcut::coupler::cutting_models {

CuttingForce evans_tensile_chip(double tensile_strength_pa, double blade_angle_deg,
                                double cut_depth_m) {
  const double alpha = radians(blade_angle_deg);
  const double s = std::sin(0.5 * alpha);  // theta = (pi/2 - alpha_r) / 2 = alpha / 2
  CuttingForce f;
  f.horizontal_n_per_m = 2.0 * tensile_strength_pa * cut_depth_m * s / (1.0 - s);
  // Frictionless face: the force on the tool is normal to it, (sin alpha, -cos alpha) of R.
  f.vertical_up_n_per_m = -f.horizontal_n_per_m * std::cos(alpha) / std::sin(alpha);
  return f;
}

}  // namespace rockcut::coupler::cutting_models
