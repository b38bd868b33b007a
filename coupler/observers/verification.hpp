// Analytical solutions a run is checked against (scene block `verification`). The error of every
// verification run is written to summary.json beside its wall time.
#pragma once

#include <map>
#include <span>
#include <string>
#include <vector>

#include "observers/run_observer.hpp"
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

/// The scene's verification: keeps the first and the last frame's positions and the fields the
/// solution compares, and checks the run's end against the solution.
class VerificationCheck : public RunObserver {
 public:
  /// Throws std::invalid_argument as verification_fields() does.
  explicit VerificationCheck(const rockcut::Scene& scene);
  /// The fields besides positions every frame must carry.
  const std::vector<std::string>& fields() const { return fields_; }
  void frame(const RunClock& clock, std::span<const FrameField> fields) override;
  bool finish(const RunClock& clock, Summary& summary, bool completed) override;
  void save_state(state::StateArchive& a) const override;
  void load_state(const state::StateArchive& a) override;

 private:
  const rockcut::Scene& scene_;
  std::vector<std::string> fields_;
  std::vector<double> initial_position_, last_position_;
  std::map<std::string, std::vector<double>> final_fields_;
};

}  // namespace rockcut::coupler
