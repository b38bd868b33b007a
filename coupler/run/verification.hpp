// Analytical solutions a run is checked against (scene block `verification`). The error of every
// verification run is written to summary.json beside its wall time.
#pragma once

#include <span>
#include <string>

#include "rockcut/scene.pb.h"

namespace rockcut::coupler {

struct VerificationResult {
  std::string analytical;      ///< the solution's name
  double error_max_rel = 0.0;  ///< max over particles of |x - x_exact| / max |x_exact - x0|
  double error_l2_rel = 0.0;   ///< ||x - x_exact||_2 / ||x_exact - x0||_2
  double tolerance_rel = 0.0;
  bool passed = false;
};

/// `uniform_acceleration`: x(t) = x0 + v0 t + a t^2 / 2 with a = gravity - grad p / density.
/// Errors are relative to the displacement, so they measure the motion, not the offset of x0.
/// `x0` and `x` are interleaved positions at t = 0 and at `time_s`.
VerificationResult verify(const rockcut::Scene& scene, std::span<const double> x0,
                          std::span<const double> x, double time_s);

}  // namespace rockcut::coupler
