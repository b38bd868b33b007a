// Local non-viscous damping (paper eq. 10, Potyondy & Cundall 2004; DESIGN section 4), per degree
// of freedom: F_d = -alpha_d |F| sign(v), for forces and moments alike, with v = v^{n+1/2}.
// always_inline: with plain inline GCC 12 compiled the step loops differently (less vectorised).
#pragma once

#include <cmath>

namespace rockcut::dem {

/// Eq. 10 for one degree of freedom: the damping force (or moment) on `force` at `velocity`.
[[gnu::always_inline]] inline double local_damping_force(double alpha, double force, double velocity) {
  return -alpha * std::abs(force) * ((velocity > 0) - (velocity < 0));
}

}  // namespace rockcut::dem
