// The pore-pressure force on a grain (paper eq. 21 with d = 2 r and unit thickness;
// DESIGN section 4): F_i = -grad p_i * pi r_i^2 [N per metre of thickness]. This is the
// `fluid.force_form: "gradient"` form; the default "adjoint" form, the negative transpose of the
// divergence that produces the pressure, is sp/operators.hpp's adjoint_pressure_force (applied in
// the step by sp/step_operator.cpp), docs/model.md says why.
#pragma once

#include <cstddef>
#include <span>

namespace rockcut::fluid::sp {

/// Eq. 21: `force` (2 per particle, overwritten) from the pressure gradient `grad` [Pa/m]
/// (2 per particle) and each grain's area pi r^2 [m^2].
inline void gradient_pressure_force(std::span<const double> grad, std::span<const double> area,
                                    std::span<double> force) {
  for (std::size_t i = 0; 2 * i < force.size(); ++i) {
    force[2 * i] = -grad[2 * i] * area[i];
    force[2 * i + 1] = -grad[2 * i + 1] * area[i];
  }
}

}  // namespace rockcut::fluid::sp
