// Analytical solutions a run is checked against (scene block `verification`). The error of every
// verification run is written to summary.json beside its wall time.
#pragma once

#include <map>
#include <span>
#include <string>
#include <vector>

#include "rockcut/scene.pb.h"

namespace rockcut::coupler {

struct VerificationResult {
  std::string analytical;      ///< the solution's name
  double error_max_rel = 0.0;  ///< max over particles of |error| / max |exact change|
  double error_l2_rel = 0.0;   ///< ||error||_2 / ||exact change||_2
  double tolerance_rel = 0.0;
  bool passed = false;
};

/// What a verification compares: the final time, the positions at t = 0 and at that time
/// (interleaved x, y), and the other final per-particle fields it asked for.
struct FinalState {
  double time_s = 0.0;
  std::span<const double> initial_position, position;
  std::map<std::string, std::span<const double>> fields;  ///< e.g. "pressure"
};

/// The per-particle fields besides positions that the scene's verification needs in the final
/// frame (e.g. "pressure"). Throws std::invalid_argument if the scene cannot be checked against
/// its analytical solution (a missing block, an inconsistent setting), naming the field.
std::vector<std::string> verification_fields(const rockcut::Scene& scene);

/// Compares the final state with the scene's analytical solution.
///  - `uniform_acceleration`: x(t) = x0 + v0 t + a t^2 / 2 with a = gravity - grad p / density;
///    errors relative to the displacement, so they measure the motion, not the offset of x0.
///  - `terzaghi`, `gaussian_pulse`, `undrained_step`: see verification_fluid.cpp.
VerificationResult verify(const rockcut::Scene& scene, const FinalState& state);

/// The pore-pressure solutions (verification_fluid.cpp).
std::vector<std::string> fluid_verification_fields(const rockcut::Scene& scene);
VerificationResult verify_fluid(const rockcut::Scene& scene, const FinalState& state);

}  // namespace rockcut::coupler
