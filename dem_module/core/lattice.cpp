#include "core/lattice.hpp"

#include <cmath>

namespace rockcut::dem {

Particles make_lattice(const LatticeSpec& spec) {
  Particles p;
  const double row = spec.hexagonal ? 0.5 * std::sqrt(3.0) * spec.spacing_m : spec.spacing_m;
  for (unsigned j = 0; j < spec.ny; ++j) {
    const double shift = spec.hexagonal && j % 2 == 1 ? 0.5 * spec.spacing_m : 0.0;
    for (unsigned i = 0; i < spec.nx; ++i) {
      p.add(spec.origin_x_m + shift + i * spec.spacing_m, spec.origin_y_m + j * row,
            spec.radius_m, spec.density_kg_m3);
    }
  }
  return p;
}

}  // namespace rockcut::dem
