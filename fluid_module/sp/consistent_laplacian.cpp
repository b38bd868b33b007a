#include "sp/consistent_laplacian.hpp"

#include "sp/operators.hpp"

namespace rockcut::fluid::sp {

void consistent_laplacian(const Geometry& geo, std::span<const double> a, std::span<double> lap) {
  laplacian(geo, a, lap);  // eq. 20, row by row
  const int n = static_cast<int>(geo.particles());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) lap[i] *= consistent_laplacian_scale(geo.l_trace[i]);
}

}  // namespace rockcut::fluid::sp
