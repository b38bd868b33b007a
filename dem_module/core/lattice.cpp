#include "core/lattice.hpp"

namespace rockcut::dem {

Particles make_lattice(const LatticeSpec& spec) {
  Particles p;
  for (unsigned j = 0; j < spec.ny; ++j) {
    for (unsigned i = 0; i < spec.nx; ++i) {
      p.add(spec.origin_x_m + i * spec.spacing_m, spec.origin_y_m + j * spec.spacing_m,
            spec.radius_m, spec.density_kg_m3);
    }
  }
  return p;
}

}  // namespace rockcut::dem
