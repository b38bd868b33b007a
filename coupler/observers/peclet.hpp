// The pore-fluid setting of a scene as the coupler reports it: the hydrostatic pressure and the
// pore Peclet number of a cut (paper eq. 2, Detournay and Atkinson 2000) with its regime.
#pragma once

#include <optional>
#include <string>

#include "observers/run_observer.hpp"
#include "rockcut/scene.pb.h"

namespace rockcut::coupler {

struct PecletNumber {
  double value = 0.0;           ///< v_c t_c / (4 D)
  double diffusivity_m2_s = 0.0;  ///< D = M kappa / mu
  std::string regime;           ///< "drained", "transient" or "undrained"
};

/// Pe = v_c t_c / (4 D) with D = M kappa / mu (eq. 2 with n C_f = 1 / M) from the scene's tool
/// (cutting velocity and depth) and fluid block. Regimes as Detournay and Atkinson: drained below
/// 0.001, undrained above 10, transient between. None without a tool or a fluid.
std::optional<PecletNumber> peclet_number(const rockcut::Scene& scene);

/// p_hydro = p_atm + rho_w g water_depth_m [Pa] (section 3.3) from the scene's fluid block.
double hydrostatic_pressure_pa(const rockcut::Scene& scene);

/// The Peclet number of a saturated cut in the start-up report and in summary.json.
class PecletReport : public RunObserver {
 public:
  explicit PecletReport(const PecletNumber& pe) : pe_(pe) {}
  void start(Summary& summary, std::vector<std::string>& report) override;

 private:
  PecletNumber pe_;
};

}  // namespace rockcut::coupler
