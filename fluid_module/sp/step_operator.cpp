#include "sp/step_operator.hpp"

#include <cstring>

#include "sp/consistent_laplacian.hpp"
#include "sp/vec2.hpp"

// Every loop is a per-particle gather over the symmetric rows, as in the operators of sp/operators.hpp: OpenMP
// threads split the particles and give the same bits for any thread count.

namespace rockcut::fluid::sp {

void StepOperator::build(const Geometry& geo) {
  const int n = static_cast<int>(geo.particles());
  c_lam_.resize(3 * geo.neighbours.size());
  t_.resize(2 * geo.neighbours.size());
  c_sum_.resize(2 * static_cast<std::size_t>(n));
  build_rows(AllRows{n}, geo);
}

bool StepOperator::rebuild_rows(const Geometry& geo, const std::vector<int>& rows) {
  if (version_ + 1 != geo.version || c_lam_.size() != 3 * geo.neighbours.size() ||
      c_sum_.size() != 2 * geo.particles()) {
    build(geo);
    return false;
  }
  build_rows(RowList{rows}, geo);
  return true;
}

template <class Rows>
void StepOperator::build_rows(const Rows& rows, const Geometry& geo) {
  const int count = rows.size();
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  const double* v = geo.volume.data();
  const double* f = geo.f.data();
  const double* inv = geo.l_inverse.data();
  const double* x = geo.position.data();
  float* cl = c_lam_.data();
  float* t = t_.data();
  double* cs = c_sum_.data();
  const bool consistent = laplacian_ == LaplacianForm::consistent;
#pragma omp parallel for schedule(static)
  for (int r = 0; r < count; ++r) {
    const int i = rows[r];
    const double* mi = inv + 3 * i;
    // 2 s_i: the row's Laplacian factor (s_i = 1 for eq. 20).
    const double two_s = consistent ? 2.0 * consistent_laplacian_scale(geo.l_trace[i]) : 2.0;
    const double xi = x[2 * i], yi = x[2 * i + 1];
    double sx = 0.0, sy = 0.0;
    for (int k = begin[i]; k < end[i]; ++k) {
      const int j = nb[k];
      const double dx = x[2 * j] - xi, dy = x[2 * j + 1] - yi;
      const double* mj = inv + 3 * j;
      // c = B_ij = -V_j F_ij L_i^{-1} d  (L^{-1} symmetric: xx, xy, yy)
      const double s = -v[j] * f[k];
      const float cx = opaque_float(s * (mi[0] * dx + mi[1] * dy));
      const float cy = opaque_float(s * (mi[1] * dx + mi[2] * dy));
      cl[3 * k] = cx;
      cl[3 * k + 1] = cy;
      cl[3 * k + 2] = static_cast<float>(two_s * v[j] * f[k]);
      sx += cx;  // C_i of the stored floats, so that the force's transpose is exact
      sy += cy;
      // t = B_ji = -V_i F_ji L_j^{-1} (x_i - x_j). Row j computes its c for i with -V_i, the same
      // F (r is the same), L_j^{-1} and -d: negations are exact, so this is the same double.
      const double u = v[i] * f[k];
      t[2 * k] = static_cast<float>(u * (mj[0] * dx + mj[1] * dy));
      t[2 * k + 1] = static_cast<float>(u * (mj[1] * dx + mj[2] * dy));
    }
    cs[2 * i] = sx;
    cs[2 * i + 1] = sy;
  }
  version_ = geo.version;
}

template <bool kLap>
void StepOperator::divergence_rows(const Geometry& geo, std::span<const double> vel,
                                   std::span<const double> a, std::span<double> div,
                                   std::span<double> lap) const {
  const int n = static_cast<int>(geo.particles());
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  const float* cl = c_lam_.data();
  const double* u = vel.data();
  const double* p = a.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const Vec2 ui = load2(u + 2 * i);
    const double ai = kLap ? p[i] : 0.0;
    Vec2 s = {0.0, 0.0};
    double l = 0.0;
    for (int k = begin[i]; k < end[i]; ++k) {
      const int j = nb[k];
      s += load2f(cl + 3 * k) * (load2(u + 2 * j) - ui);
      if constexpr (kLap) l += static_cast<double>(cl[3 * k + 2]) * (ai - p[j]);
    }
    div[i] = s[0] + s[1];
    if constexpr (kLap) lap[i] = l;
  }
}

void StepOperator::divergence(const Geometry& geo, std::span<const double> vel,
                              std::span<double> div) const {
  divergence_rows<false>(geo, vel, {}, div, {});
}

void StepOperator::divergence_laplacian(const Geometry& geo, std::span<const double> vel,
                                        std::span<const double> a, std::span<double> div,
                                        std::span<double> lap) const {
  divergence_rows<true>(geo, vel, a, div, lap);
}

void StepOperator::adjoint_force(const Geometry& geo, std::span<const double> area_q,
                                 std::span<double> force) const {
  const int n = static_cast<int>(geo.particles());
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  const float* t = t_.data();
  const double* cs = c_sum_.data();
  const double* g = area_q.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    Vec2 s = {0.0, 0.0};
    for (int k = begin[i]; k < end[i]; ++k) s += load2f(t + 2 * k) * g[nb[k]];
    const Vec2 fi = s - g[i] * load2(cs + 2 * i);  // sum_j A_j q_j B_ji - A_i q_i sum_j B_ij
    std::memcpy(force.data() + 2 * i, &fi, sizeof fi);
  }
}

}  // namespace rockcut::fluid::sp
