#include "models/implicit_model.hpp"

#include "models/fluid_points_model.hpp"
#include "models/registry.hpp"
#include "sp/format.hpp"

namespace rockcut::fluid::sp {

ImplicitModel::ImplicitModel(const SpParams& params)
    : PorePressureModel(params), system_(params.solver_tolerance, params.solver_max_iterations, params.laplacian) {}

StabilityLimit ImplicitModel::diffusion_limit() const {
  const double h = params_.h_m;
  return {"implicit_accuracy", params_.max_diffusion_number * h * h / diffusivity_m2_s_,
          "accuracy, not stability: max_diffusion_number h^2 / D with max_diffusion_number = " +
              fmt(params_.max_diffusion_number) + ", h = " + fmt(h) + " m, D = " +
              fmt(diffusivity_m2_s_) + " m^2/s",
          /*lag_only=*/false, /*remedy=*/{}};
}

void ImplicitModel::advance(double dt_s) {
  last_ = system_.step(dt_s, diffusivity_m2_s_, geo_, source_, boundary_,
                       params_.p_hydro_pa, params_.cavitation, params_.p_min_pa, pressure_);
}

void ImplicitModel::add_scalars(std::vector<std::pair<std::string, double>>& out) const {
  out.emplace_back("solver_iterations", static_cast<double>(last_.iterations));
  out.emplace_back("active_set_rounds", static_cast<double>(last_.rounds));
}

}  // namespace rockcut::fluid::sp

namespace rockcut::fluid {
namespace {
// Registered by name at static initialisation (models/registry.hpp); the archive is linked whole.
// On fewer points than grains with fluid.point_spacing > 1 (models/fluid_points_model.hpp).
const bool registered = register_model("implicit", [](const wire::FluidConfig& config) {
  return sp::pore_pressure_model(sp::sp_params_from_config(config), [](const sp::SpParams& p) {
    return std::unique_ptr<sp::PorePressureModel>(std::make_unique<sp::ImplicitModel>(p));
  });
});
}  // namespace
}  // namespace rockcut::fluid
