#include "sp/operators.hpp"

#include <algorithm>

namespace rockcut::fluid::sp {

void gradient(const NeighbourList& list, const Geometry& geo, std::span<const double> a,
              std::span<double> grad) {
  const int n = static_cast<int>(list.particles());
  const int* off = list.offsets().data();
  const int* nb = list.neighbours().data();
  const double* v = geo.volume.data();
  const double* inv = geo.l_inverse.data();
  const double* x = geo.position.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    // grad_i W_ij = F_ij (x_i - x_j) = -F_ij (dx, dy).
    double sx = 0.0, sy = 0.0;
    const double ai = a[i], xi = x[2 * i], yi = x[2 * i + 1];
    for (int k = off[i]; k < off[i + 1]; ++k) {
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

void divergence(const NeighbourList& list, const Geometry& geo, std::span<const double> vel,
                std::span<double> div) {
  const int n = static_cast<int>(list.particles());
  const int* off = list.offsets().data();
  const int* nb = list.neighbours().data();
  const double* v = geo.volume.data();
  const double* inv = geo.l_inverse.data();
  const double* x = geo.position.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    // G_ab = sum_j V_j (v_j - v_i)_a (grad_i W_ij)_b; div = trace(G L^{-1}).
    double gxx = 0.0, gxy = 0.0, gyx = 0.0, gyy = 0.0;
    const double ux = vel[2 * i], uy = vel[2 * i + 1], xi = x[2 * i], yi = x[2 * i + 1];
    for (int k = off[i]; k < off[i + 1]; ++k) {
      const int j = nb[k];
      const double s = -v[j] * geo.f[k];
      const double du = vel[2 * j] - ux, dv = vel[2 * j + 1] - uy;
      const double wx = s * (x[2 * j] - xi), wy = s * (x[2 * j + 1] - yi);
      gxx += du * wx;
      gxy += du * wy;
      gyx += dv * wx;
      gyy += dv * wy;
    }
    const double* m = inv + 3 * i;
    div[i] = gxx * m[0] + (gxy + gyx) * m[1] + gyy * m[2];
  }
}

void adjoint_pressure_force(const NeighbourList& list, const Geometry& geo,
                            std::span<const double> area, std::span<const double> q,
                            std::span<double> force) {
  const int n = static_cast<int>(list.particles());
  const int* off = list.offsets().data();
  const int* nb = list.neighbours().data();
  const double* v = geo.volume.data();
  const double* inv = geo.l_inverse.data();
  const double* x = geo.position.data();
  // The pair term A_i q_i B_ij, with B_ij = L_i^{-1} V_j grad_i W_ij and grad_i W_ij =
  // -F_ij (x_j - x_i), pushes j and pulls i back. Gathered per particle over its (symmetric) row:
  // F_i = sum_j (A_j q_j B_ji - A_i q_i B_ij), so threads write only their own particles.
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double aqi = area[i] * q[i];
    const double xi = x[2 * i], yi = x[2 * i + 1];
    const double* mi = inv + 3 * i;
    double fx = 0.0, fy = 0.0;
    for (int k = off[i]; k < off[i + 1]; ++k) {
      const int j = nb[k];
      const double dx = x[2 * j] - xi, dy = x[2 * j + 1] - yi;  // x_j - x_i
      // B_ij on i: -(A_i q_i) L_i^{-1} V_j (-F_ij) (x_j - x_i).
      const double si = -aqi * v[j] * geo.f[k];
      const double gxi = si * dx, gyi = si * dy;
      fx -= mi[0] * gxi + mi[1] * gyi;
      fy -= mi[1] * gxi + mi[2] * gyi;
      // B_ji on i: (A_j q_j) L_j^{-1} V_i (-F_ji) (x_i - x_j), F_ji = F_ij.
      const double aqj = area[j] * q[j];
      if (aqj != 0.0) {
        const double* mj = inv + 3 * j;
        const double sj = aqj * v[i] * geo.f[k];  // -(-F) with (x_i - x_j) = -(dx, dy)
        const double gxj = sj * dx, gyj = sj * dy;
        fx += mj[0] * gxj + mj[1] * gyj;
        fy += mj[1] * gxj + mj[2] * gyj;
      }
    }
    force[2 * i] = fx;
    force[2 * i + 1] = fy;
  }
}

void laplacian(const NeighbourList& list, const Geometry& geo, std::span<const double> a,
               std::span<double> lap) {
  const int n = static_cast<int>(list.particles());
  const int* off = list.offsets().data();
  const int* nb = list.neighbours().data();
  const double* v = geo.volume.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double s = 0.0;
    const double ai = a[i];
    for (int k = off[i]; k < off[i + 1]; ++k) {
      const int j = nb[k];
      s += v[j] * (ai - a[j]) * geo.f[k];
    }
    lap[i] = 2.0 * s;
  }
}

void interpolate(const NeighbourList& list, const Geometry& geo, double w0,
                 std::span<const double> a, std::span<const double> grad,
                 std::span<double> out) {
  const int n = static_cast<int>(list.particles());
  const int* off = list.offsets().data();
  const int* nb = list.neighbours().data();
  const double* v = geo.volume.data();
  const double* x = geo.position.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double num = v[i] * a[i] * w0, den = v[i] * w0, mx = 0.0, my = 0.0;
    const double xi = x[2 * i], yi = x[2 * i + 1];
    for (int k = off[i]; k < off[i + 1]; ++k) {
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

void volume_sum(const NeighbourList& list, const Geometry& geo, double w0, std::span<double> out) {
  const int n = static_cast<int>(list.particles());
  const int* off = list.offsets().data();
  const int* nb = list.neighbours().data();
  const double* v = geo.volume.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double s = v[i] * w0;
    for (int k = off[i]; k < off[i + 1]; ++k) s += v[nb[k]] * geo.w[k];
    out[i] = s;
  }
}

}  // namespace rockcut::fluid::sp
