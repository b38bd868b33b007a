#include "scene/particle_budget.hpp"

#include <cmath>
#include <numbers>

#include "scene/format.hpp"

namespace rockcut::scene {

std::optional<std::string> particle_budget_problem(const rockcut::Scene& scene) {
  if (!scene.has_dem()) return std::nullopt;
  return particle_budget_problem(scene.dem());
}

std::optional<std::string> particle_budget_problem(const rockcut::Dem& dem) {
  const auto limit = static_cast<double>(kMaxParticles);
  const std::string allowed = "; at most " + std::to_string(kMaxParticles) + " particles are allowed";
  if (dem.has_lattice()) {
    const double n = static_cast<double>(dem.lattice().nx()) * dem.lattice().ny();
    if (n > limit) {
      return "dem.lattice: nx * ny = " + format_double(n) + " discs" + allowed;
    }
  }
  if (dem.has_specimen()) {
    // Discs no smaller than radius_min_m cannot cover more than the outline's area.
    const rockcut::Specimen& s = dem.specimen();
    const double area = s.shape() == "circle"
                            ? std::numbers::pi / 4 * s.diameter_m() * s.diameter_m()
                            : s.width_m() * s.height_m();
    const double r = s.radius_min_m();
    const double n = r > 0 ? area / (std::numbers::pi * r * r) : 0.0;
    if (!(n <= limit) && std::isfinite(area) && r > 0) {
      return "dem.specimen: up to " + format_double(n) + " discs of radius_min_m " +
             format_double(r) + " m fit in it" + allowed;
    }
  }
  return std::nullopt;
}

}  // namespace rockcut::scene
