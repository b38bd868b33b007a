// Choosing the DEM step dt and the coupling interval N from the stability limits the modules report
// (DESIGN section 5), or checking the scene's own choice against them.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcut/scene.pb.h"
#include "rockcut/wire.pb.h"

namespace rockcut::coupler {

/// A stability limit as reported by a module.
struct Limit {
  std::string module;  ///< "dem_module", "fluid_module"
  std::string name;     ///< for the report; the coupler picks limits by `kind`
  double dt_max_s = 0.0;
  std::string detail;
  bool lag_only = false;  ///< bounds only N > 1 (a lagged coupling); N = 1 is always allowed
  std::string remedy;     ///< what else to change when it refuses a scene
  wire::LimitKind kind = wire::LIMIT_KIND_UNSPECIFIED;  ///< what it bounds
};

/// The scene asks for more than a limit allows. what() names the limit, by how much it is exceeded
/// and what to change.
class PlanError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TimePlan {
  double dt_s = 0.0;
  unsigned coupling_interval = 1;  ///< N: DEM steps per fluid step (1 for a dry scene)
  std::uint64_t total_steps = 0;
  std::string binding;             ///< which limit or setting fixed dt
  /// The DEM computes its forces before answering its kinematics (run/overlap_choice.hpp).
  bool forces_before_reply = false;
  /// The DEM extrapolates the fluid's force between exchanges (Coupling.fluid_force
  /// "extrapolated" and N > 1; at N = 1 there is nothing between exchanges).
  bool extrapolate_fluid_force = false;
  /// The DEM takes out the lag's generated energy (Coupling.lag_correction "passivity", N > 1).
  bool lag_passivity = false;
  /// The DEM applies each grain's own fluid stiffness between exchanges (Coupling.fluid_stiffness
  /// "self", N > 1).
  bool fluid_self_stiffness = false;
  std::vector<std::string> report; ///< one line per limit and choice, printed at start-up
};

/// dem_limits bound dt; fluid_limits bound the fluid step N * dt.
TimePlan plan_time(const rockcut::Scene& scene, const std::vector<Limit>& dem_limits,
                   const std::vector<Limit>& fluid_limits, bool coupled);

/// The smallest of `limits` [s], or 0 when there is none.
double smallest_limit_s(const std::vector<Limit>& limits);

/// The fluid limits that bound the scene: of the pore fluid's two stiffness limits, the one for
/// the way its Coupling.fluid_force applies the force between exchanges (held or extrapolated).
/// With the lag's energy taken out (Coupling.lag_correction "passivity") the extrapolated force's
/// stiffness limit is this many times the fluid's. Measured on the reduced dynamic cut over sixteen
/// seeds (docs/record/accuracy.md, "The lag's energy taken out"): at 8 dt, 1.61 times the limit,
/// the forces and the pore fluid's share of the tool's work stay N = 1's at 0 and 2000 m; at
/// 16 dt, 3.2 times, the correction takes over the fluid's dissipation. 1.65 lets that N = 8 be
/// chosen at both scales (the limit keeps its ratio to the DEM step at every disc size); at paper
/// scale it kept the forces but not the fluid's share (docs/record/results.md, "The lag's energy
/// taken out at paper scale"), so that scene does not ask for the correction.
inline constexpr double kLagPassivityLimitFactor = 1.65;

std::vector<Limit> applicable_fluid_limits(const rockcut::Scene& scene, std::vector<Limit> limits);

/// The pore-fluid stiffness limit among `limits` (LIMIT_KIND_PORE_FLUID_STIFFNESS or
/// LIMIT_KIND_PORE_FLUID_STIFFNESS_EXTRAPOLATED, whatever its name, the first of them) [s], or 0
/// when none is reported: the expected coupling-lag error is read against it. Pass the applicable
/// limits.
double pore_fluid_stiffness_limit_s(const std::vector<Limit>& limits);

}  // namespace rockcut::coupler
