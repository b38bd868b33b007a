#include "sp/params.hpp"

#include <stdexcept>

#include "rockcut/wire.pb.h"
#include "sp/format.hpp"

namespace rockcut::fluid::sp {

SpParams sp_params_from_config(const wire::FluidConfig& config) {
  const rockcut::Fluid& f = config.fluid();
  if (!config.has_solid()) {
    throw std::invalid_argument(
        "fluid.model \"" + f.model() + "\" needs the solid's properties (Init.fluid.solid: grain "
        "density, local damping, whether the solid is dynamic and sealed at walls), which the "
        "DEM sends in its InitReply.solid and the coupler forwards; this Init has none");
  }
  const wire::SolidProperties& solid = config.solid();
  SpParams p;
  p.h_m = f.smoothing_length_m();
  p.alpha = f.biot_coefficient();
  p.bulk_modulus_pa = f.bulk_modulus_pa();
  p.permeability_m2 = f.permeability_m2();
  p.viscosity_pa_s = f.viscosity_pa_s();
  p.water_density_kg_m3 = f.water_density_kg_m3();
  p.open_water_drag = f.open_water_drag();
  p.point_spacing = f.point_spacing();
  if (p.point_spacing > 1.0 && p.open_water_drag) {
    throw std::invalid_argument(
        "fluid.open_water_drag acts on single grains and fluid.point_spacing = " +
        fmt(p.point_spacing) +
        " puts the pore fluid on points of several grains; use one of them");
  }
  // Section 3.3: p_hydro = p_atm + rho_w g H. The pressure is absolute.
  p.p_hydro_pa = f.atmospheric_pressure_pa() +
                 f.water_density_kg_m3() * f.gravity_m_s2() * config.water_depth_m();
  p.surface_div_r = f.surface_div_r();
  for (const std::string& side : f.sealed_sides()) {
    if (side == "left") p.sealed[0] = true;
    if (side == "right") p.sealed[1] = true;
    if (side == "bottom") p.sealed[2] = true;
    if (side == "top") p.sealed[3] = true;
  }
  p.seal_at_walls = solid.seals_at_walls();
  p.grain_density_kg_m3 = solid.grain_density_kg_m3();
  p.dynamic_solid = solid.dynamic();
  p.local_damping = solid.local_damping();
  p.viscous_damping_ratio = solid.viscous_damping_ratio();
  p.normal_stiffness_pa = solid.normal_stiffness_pa();
  p.cavitation = f.cavitation();
  p.p_min_pa = f.cavitation_pressure_pa();
  p.strain_from = f.strain_from() == "velocity_half" ? StrainFrom::velocity_half
                                                     : StrainFrom::displacement;
  p.force_form = f.force_form() == "gradient" ? ForceForm::gradient : ForceForm::adjoint;
  p.laplacian = f.laplacian() == "consistent" ? LaplacianForm::consistent : LaplacianForm::paper;
  p.volume_iterations = f.volume_iterations();
  p.skin = f.neighbour_skin();
  p.geometry_refresh = f.geometry_refresh_distance();
  p.solver_tolerance = f.implicit().tolerance();
  p.solver_max_iterations = f.implicit().max_iterations();
  p.max_diffusion_number = f.implicit().max_diffusion_number();
  if (f.has_initial_pulse()) {
    p.pulse_amplitude_pa = f.initial_pulse().amplitude_pa();
    p.pulse_x_m = f.initial_pulse().centre_m().x();
    p.pulse_y_m = f.initial_pulse().centre_m().y();
    p.pulse_sigma_m = f.initial_pulse().sigma_m();
  }
  if (p.cavitation && !(p.p_min_pa < p.p_hydro_pa)) {
    throw std::invalid_argument(
        "fluid.cavitation_pressure_pa = " + std::to_string(p.p_min_pa) +
        " Pa is not below the hydrostatic pressure p_hydro = " + std::to_string(p.p_hydro_pa) +
        " Pa (fluid.atmospheric_pressure_pa + fluid.water_density_kg_m3 * fluid.gravity_m_s2 * "
        "water_depth_m): the initial state would be cavitated; lower it or set fluid.cavitation: "
        "false");
  }
  if (p.cavitation && p.pulse_amplitude_pa < 0.0 &&
      p.p_hydro_pa + p.pulse_amplitude_pa < p.p_min_pa) {
    throw std::invalid_argument(
        "fluid.initial_pulse.amplitude_pa takes the pressure below fluid.cavitation_pressure_pa");
  }
  return p;
}

}  // namespace rockcut::fluid::sp
