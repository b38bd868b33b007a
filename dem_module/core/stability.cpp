#include "core/stability.hpp"

#include <cmath>
#include <cstdio>

#include "core/viscous_damping.hpp"

namespace rockcut::dem {

CriticalStep critical_step(const Particles& p, double kn, double ks, double damping_ratio,
                           bool rolling_springs) {
  CriticalStep best;
  if (kn <= 0 && ks <= 0) return best;
  double dt = 1e300;
  std::size_t which = 0;
  const char* mode = "";
  const double rotation_stiffness = rolling_springs ? 2.0 * ks : ks;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double m = 1.0 / p.inv_mass[i], inertia = 1.0 / p.inv_inertia[i], r = p.radius[i];
    const double candidates[3] = {kn > 0 ? std::sqrt(m / kn) : 1e300,
                                  ks > 0 ? std::sqrt(m / ks) : 1e300,
                                  ks > 0 ? std::sqrt(inertia / (rotation_stiffness * r * r)) : 1e300};
    const char* names[3] = {"sqrt(m/k_n)", "sqrt(m/k_s)",
                            rolling_springs ? "sqrt(I/(2 k_s r^2))" : "sqrt(I/(k_s r^2))"};
    for (int c = 0; c < 3; ++c) {
      if (candidates[c] < dt) {
        dt = candidates[c];
        which = i;
        mode = names[c];
      }
    }
  }
  if (p.size() == 0) return best;
  char detail[220];
  const int written = std::snprintf(detail, sizeof detail, "%s of disc %zu (r = %.3g m), k_n %.3g, k_s %.3g Pa",
                                    mode, which, p.radius[which], kn, ks);
  if (damping_ratio > 0) {
    const double factor = damped_critical_step_factor(damping_ratio);
    dt *= factor;
    std::snprintf(detail + written, sizeof detail - static_cast<std::size_t>(written),
                  ", times sqrt(1 + zeta^2) - zeta = %.3g for dashpots of zeta %.3g", factor,
                  damping_ratio);
  }
  best.dt_s = dt;
  best.detail = detail;
  return best;
}

}  // namespace rockcut::dem
