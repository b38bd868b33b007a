// CSPM interpolation, paper eq. 15, and the partition of unity sum_j V_j W_ij: declared in
// sp/operators.hpp.
#include "sp/operators.hpp"

namespace rockcut::fluid::sp {

void interpolate(const Geometry& geo, double w0, std::span<const double> a,
                 std::span<const double> grad, std::span<double> out) {
  const int n = static_cast<int>(geo.particles());
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  const double* v = geo.volume.data();
  const double* x = geo.position.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double num = v[i] * a[i] * w0, den = v[i] * w0, mx = 0.0, my = 0.0;
    const double xi = x[2 * i], yi = x[2 * i + 1];
    for (int k = begin[i]; k < end[i]; ++k) {
      const int j = nb[k];
      const double vw = v[j] * geo.w[k];
      num += vw * a[j];
      den += vw;
      mx += vw * (x[2 * j] - xi);
      my += vw * (x[2 * j + 1] - yi);
    }
    out[i] = (num - grad[2 * i] * mx - grad[2 * i + 1] * my) / den;
  }
}

void volume_sum(const Geometry& geo, double w0, std::span<double> out) {
  const int n = static_cast<int>(geo.particles());
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  const double* v = geo.volume.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double s = v[i] * w0;
    for (int k = begin[i]; k < end[i]; ++k) s += v[nb[k]] * geo.w[k];
    out[i] = s;
  }
}

}  // namespace rockcut::fluid::sp
