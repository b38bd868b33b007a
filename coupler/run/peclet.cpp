#include "run/peclet.hpp"

namespace rockcut::coupler {

std::optional<PecletNumber> peclet_number(const rockcut::Scene& scene) {
  if (!scene.has_fluid() || !scene.dem().has_tool()) return std::nullopt;
  const rockcut::Fluid& f = scene.fluid();
  const rockcut::Tool& tool = scene.dem().tool();
  PecletNumber pe;
  pe.diffusivity_m2_s = f.bulk_modulus_pa() * f.permeability_m2() / f.viscosity_pa_s();
  pe.value = tool.velocity_m_s() * tool.cutting_depth_m() / (4.0 * pe.diffusivity_m2_s);
  pe.regime = pe.value < 1e-3 ? "drained" : pe.value > 10.0 ? "undrained" : "transient";
  return pe;
}

double hydrostatic_pressure_pa(const rockcut::Scene& scene) {
  const rockcut::Fluid& f = scene.fluid();
  return f.atmospheric_pressure_pa() +
         f.water_density_kg_m3() * f.gravity_m_s2() * scene.water_depth_m();
}

}  // namespace rockcut::coupler
