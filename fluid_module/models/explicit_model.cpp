#include "models/explicit_model.hpp"

#include <algorithm>
#include <stdexcept>

#include "models/fluid_points_model.hpp"
#include "models/registry.hpp"
#include "sp/cavitation.hpp"
#include "sp/format.hpp"
#include "sp/operators.hpp"
#include "sp/storage_equation.hpp"

namespace rockcut::fluid::sp {

ExplicitModel::ExplicitModel(const SpParams& params)
    : PorePressureModel(params),
      dt_max_s_(kExplicitStabilityC * params.h_m * params.h_m / diffusivity_m2_s_) {
  laplacian_in_step_ = true;  // lap p^n comes with the divergence's pass over the pairs
}

StabilityLimit ExplicitModel::diffusion_limit() const {
  return {"explicit_diffusion", dt_max_s_,
          "C h^2 / D with C = " + fmt(kExplicitStabilityC) + ", h = " + fmt(params_.h_m) +
              " m, D = M kappa / mu = " + fmt(diffusivity_m2_s_) + " m^2/s",
          false, "use fluid.model: \"implicit\", which has no diffusion limit"};
}

void ExplicitModel::advance(double dt_s) {
  // A relative margin of 1e-9 absorbs the round-off of N * dt computed by the coupler.
  if (dt_s > dt_max_s_ * (1.0 + 1e-9)) {
    throw std::invalid_argument(
        "explicit: the fluid step " + fmt(dt_s) + " s exceeds the stability limit C h^2 / D = " +
        fmt(dt_max_s_) + " s (C = " + fmt(kExplicitStabilityC) + ", h = " + fmt(params_.h_m) +
        " m, D = " + fmt(diffusivity_m2_s_) + " m^2/s) by " + fmt(dt_s / dt_max_s_) +
        "x; shorten the fluid step (time.dt_s, coupling.interval) or use fluid.model: "
        "\"implicit\"");
  }
  // laplacian_ = lap p^n everywhere, computed by step() before any update.
  const double p_min = params_.p_min_pa;
  const std::size_t n = pressure_.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (boundary_[i] == Boundary::drained) {
      pressure_[i] = params_.p_hydro_pa;  // section 3.3: Dirichlet where the surface meets water
      continue;
    }
    const double rate = storage_rate(diffusivity_m2_s_, laplacian_[i], source_[i]);  // eq. 14
    if (params_.cavitation) {
      pressure_[i] = cavitation_limited_step(pressure_[i], rate, dt_s, p_min);  // eq. 22
    } else {
      pressure_[i] += dt_s * rate;
    }
  }
}

}  // namespace rockcut::fluid::sp

namespace rockcut::fluid {
namespace {
// Registered by name at static initialisation (models/registry.hpp); the archive is linked whole.
// On fewer points than grains with fluid.point_spacing > 1 (models/fluid_points_model.hpp).
const bool registered = register_model("explicit", [](const wire::FluidConfig& config) {
  return sp::pore_pressure_model(sp::sp_params_from_config(config), [](const sp::SpParams& p) {
    return std::unique_ptr<sp::PorePressureModel>(std::make_unique<sp::ExplicitModel>(p));
  });
});
}  // namespace
}  // namespace rockcut::fluid
