#include "sp/operators.hpp"

#include <algorithm>

#include "sp/vec2.hpp"

namespace rockcut::fluid::sp {

namespace {

// The rows of divergence() and laplacian(), alone or together (kDiv, kLap). Every sum has the same
// terms in the same order whichever of the two is computed, so the fused call gives the bits of
// the separate ones. (Two sets of accumulators for even and odd pairs, to shorten the chains of
// dependent additions, made the pass 7 % slower: with SSE2's 16 registers the sums spill.)
template <bool kDiv, bool kLap>
void divergence_laplacian_rows(const Geometry& geo, std::span<const double> vel,
                               std::span<const double> a, std::span<double> div,
                               std::span<double> lap) {
  const int n = static_cast<int>(geo.particles());
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  const double* v = geo.volume.data();
  const double* f = geo.f.data();
  const double* inv = geo.l_inverse.data();
  const double* x = geo.position.data();
  const double* u = vel.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    // Divergence: G_ab = sum_j V_j (v_j - v_i)_a (grad_i W_ij)_b with grad_i W_ij = -F_ij (x_j -
    // x_i); div = trace(G L^{-1}). Row a of G is g_a = sum_j (v_j - v_i)_a w_ij with
    // w_ij = -V_j F_ij (x_j - x_i). Laplacian (eq. 20): sum_j 2 V_j (a_i - a_j) F_ij.
    Vec2 gx = {0.0, 0.0}, gy = {0.0, 0.0};  // (G_xx, G_xy), (G_yx, G_yy)
    double l = 0.0;
    const Vec2 xi = load2(x + 2 * i);
    const Vec2 ui = kDiv ? load2(u + 2 * i) : Vec2{0.0, 0.0};
    const double ai = kLap ? a[i] : 0.0;
    for (int k = begin[i]; k < end[i]; ++k) {
      const int j = nb[k];
      if constexpr (kDiv) {
        const double s = -v[j] * f[k];
        const Vec2 du = load2(u + 2 * j) - ui;
        const Vec2 w = s * (load2(x + 2 * j) - xi);
        gx += du[0] * w;
        gy += du[1] * w;
      }
      if constexpr (kLap) l += v[j] * (ai - a[j]) * f[k];
    }
    if constexpr (kDiv) {
      const double* m = inv + 3 * i;
      div[i] = gx[0] * m[0] + (gx[1] + gy[0]) * m[1] + gy[1] * m[2];
    }
    if constexpr (kLap) lap[i] = 2.0 * l;
  }
}

}  // namespace

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

void divergence(const Geometry& geo, std::span<const double> vel, std::span<double> div) {
  divergence_laplacian_rows<true, false>(geo, vel, {}, div, {});
}

void laplacian(const Geometry& geo, std::span<const double> a, std::span<double> lap) {
  divergence_laplacian_rows<false, true>(geo, {}, a, {}, lap);
}

void divergence_laplacian(const Geometry& geo, std::span<const double> vel,
                          std::span<const double> a, std::span<double> div,
                          std::span<double> lap) {
  divergence_laplacian_rows<true, true>(geo, vel, a, div, lap);
}

void adjoint_pressure_force(const Geometry& geo, std::span<const double> area,
                            std::span<const double> q, std::span<double> force,
                            std::span<double> work) {
  const int n = static_cast<int>(geo.particles());
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  const double* v = geo.volume.data();
  const double* inv = geo.l_inverse.data();
  const double* x = geo.position.data();
  const double* f = geo.f.data();
  double* p = work.data();
  // F_i = sum_j (A_j q_j B_ji - A_i q_i B_ij) with B_ij = -V_j F_ij L_i^{-1} (x_j - x_i), the
  // per-pair sums gathered over i's (symmetric) row so that threads write only their own
  // particles. Both terms factor into per-particle quantities and two sums over the row:
  //   sum_j A_i q_i B_ij = -A_i q_i L_i^{-1} S1_i,   S1_i = sum_j F_ij V_j (x_j - x_i),
  //   sum_j A_j q_j B_ji =  V_i S2_i,                 S2_i = sum_j F_ij P_j (x_j - x_i),
  // with P_j = A_j q_j L_j^{-1} computed first. The pair loop then does 13 flops instead of 30.
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      const double aq = area[i] * q[i];
      const double* m = inv + 3 * i;
      p[3 * i] = aq * m[0];
      p[3 * i + 1] = aq * m[1];
      p[3 * i + 2] = aq * m[2];
    }
    // (the implied barrier: every P_j is written before any row reads it)
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      const Vec2 xi = load2(x + 2 * i);
      Vec2 s1 = {0.0, 0.0}, s2 = {0.0, 0.0};
      for (int k = begin[i]; k < end[i]; ++k) {
        const int j = nb[k];
        const Vec2 fd = f[k] * (load2(x + 2 * j) - xi);  // (fx, fy) = F_ij (x_j - x_i)
        s1 += v[j] * fd;
        // P_j is symmetric (xx, xy, yy): (P_xx fx + P_xy fy, P_xy fx + P_yy fy).
        s2 += load2(p + 3 * j) * fd[0] + load2(p + 3 * j + 1) * fd[1];
      }
      const double* pi = p + 3 * i;  // A_i q_i L_i^{-1}
      force[2 * i] = (pi[0] * s1[0] + pi[1] * s1[1]) + v[i] * s2[0];
      force[2 * i + 1] = (pi[1] * s1[0] + pi[2] * s1[1]) + v[i] * s2[1];
    }
  }
}

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
