// CSPM gradient, paper eq. 16 (Chen et al. 1999): declared in sp/operators.hpp.
#include "sp/operators.hpp"

namespace rockcut::fluid::sp {

void gradient(const Geometry& geo, std::span<const double> a, std::span<double> grad) {
  const int n = static_cast<int>(geo.particles());
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  const double* v = geo.volume.data();
  const double* inv = geo.l_inverse.data();
  const double* x = geo.position.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    // grad_i W_ij = F_ij (x_i - x_j) = -F_ij (dx, dy).
    double sx = 0.0, sy = 0.0;
    const double ai = a[i], xi = x[2 * i], yi = x[2 * i + 1];
    for (int k = begin[i]; k < end[i]; ++k) {
      const int j = nb[k];
      const double s = v[j] * (a[j] - ai) * -geo.f[k];
      sx += s * (x[2 * j] - xi);
      sy += s * (x[2 * j + 1] - yi);
    }
    const double* m = inv + 3 * i;
    grad[2 * i] = m[0] * sx + m[1] * sy;
    grad[2 * i + 1] = m[1] * sx + m[2] * sy;
  }
}

}  // namespace rockcut::fluid::sp
