// The DEM's critical time step (DESIGN section 5): dt <= safety * min sqrt(m / k) over particles
// and springs, rotation included.
#pragma once

#include <string>

#include "core/particles.hpp"

namespace rockcut::dem {

struct CriticalStep {
  double dt_s = 0.0;
  std::string detail;  ///< which mode of which disc binds, for the start-up report
};

/// The smallest of sqrt(m / k_n), sqrt(m / k_s) (translation) and sqrt(I / (k_s r^2)) (rotation of
/// a disc about its centre under a tangential spring at its rim; sqrt(I / (2 k_s r^2)) with
/// rolling springs, whose stiffness against a wall is k_s r^2 again) over all discs, with the
/// largest normal and shear stiffness of any spring, times sqrt(1 + zeta^2) - zeta for dashpots
/// of damping ratio zeta (core/viscous_damping.hpp). 0 stiffness: no limit (dt_s = 0).
CriticalStep critical_step(const Particles& p, double normal_stiffness_pa,
                           double shear_stiffness_pa, double damping_ratio = 0.0,
                           bool rolling_springs = false);

}  // namespace rockcut::dem
