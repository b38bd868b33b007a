#include "cutting_models/hyperbaric_flow_type.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockcut::coupler::cutting_models {

double cavitation_under_pressure_pa(double water_depth_m, double water_density_kg_m3,
                                    double gravity_m_s2, double atmospheric_pressure_pa,
                                    double vapour_pressure_pa) {
  return std::max(0.0, atmospheric_pressure_pa + water_density_kg_m3 * gravity_m_s2 * water_depth_m -
                           vapour_pressure_pa);
}

FlowTypeForce hyperbaric_flow_type(double cohesion_pa, double friction_angle_deg,
                                   double tool_friction_angle_deg, double blade_angle_deg,
                                   double cut_depth_m, double blade_height_m,
                                   double under_pressure_pa) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  FlowTypeForce best;
  best.force = {kNaN, kNaN};
  best.shear_angle_deg = kNaN;
  // beta ranges over (0, 180 - alpha - delta - phi) deg, where sin(alpha+beta+delta+phi) > 0.
  const double beta_max_deg = 180.0 - blade_angle_deg - tool_friction_angle_deg - friction_angle_deg;
  if (beta_max_deg <= 0.0) return best;
  const auto horizontal = [&](double beta_deg) {
    return flow_type_at_shear_angle(cohesion_pa, friction_angle_deg, tool_friction_angle_deg,
                                    blade_angle_deg, cut_depth_m, blade_height_m,
                                    under_pressure_pa, beta_deg)
        .horizontal_n_per_m;
  };
  // The force grows without bound at both ends of the range (sin(beta) -> 0 and
  // sin(alpha+beta+delta+phi) -> 0); a scan brackets its least value, a golden-section search
  // refines it to 1e-9 deg.
  constexpr int kScan = 2000;
  const double step = beta_max_deg / kScan;
  int best_k = 1;
  double best_f = std::numeric_limits<double>::infinity();
  for (int k = 1; k < kScan; ++k) {
    const double f = horizontal(k * step);
    if (f < best_f) best_f = f, best_k = k;
  }
  double lo = (best_k - 1) * step, hi = (best_k + 1) * step;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = horizontal(x1), f2 = horizontal(x2);
  while (hi - lo > 1e-9) {
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = horizontal(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = horizontal(x2);
    }
  }
  best.shear_angle_deg = 0.5 * (lo + hi);
  best.force = flow_type_at_shear_angle(cohesion_pa, friction_angle_deg, tool_friction_angle_deg,
                                        blade_angle_deg, cut_depth_m, blade_height_m,
                                        under_pressure_pa, best.shear_angle_deg);
  return best;
}

}  // namespace rockcut::coupler::cutting_models
