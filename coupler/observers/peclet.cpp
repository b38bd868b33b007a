#include "observers/peclet.hpp"

#include <cstdio>

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

void PecletReport::start(Summary& summary, std::vector<std::string>& report) {
  summary.set("peclet_number", pe_.value);
  summary.set("regime", pe_.regime);
  char line[256];
  std::snprintf(line, sizeof line,
                "peclet     Pe = v_c t_c / (4 D) = %.3g (D = M kappa / mu = %.3g m^2/s): %s "
                "regime (drained < 0.001 < transient < 10 < undrained)",
                pe_.value, pe_.diffusivity_m2_s, pe_.regime.c_str());
  report.push_back(line);
}

}  // namespace rockcut::coupler
