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
  std::fill(force.begin(), force.end(), 0.0);
  for (int i = 0; i < n; ++i) {
    const double aq = area[i] * q[i];
    if (aq == 0.0) continue;
    const double xi = x[2 * i], yi = x[2 * i + 1];
    const double* m = inv + 3 * i;
    for (int k = off[i]; k < off[i + 1]; ++k) {
      const int j = nb[k];
      // A_i q_i B_ij, with grad_i W_ij = -F_ij (x_j - x_i); it pushes j and pulls i back.
      const double s = -aq * v[j] * geo.f[k];
      const double gx = s * (x[2 * j] - xi), gy = s * (x[2 * j + 1] - yi);
      const double bx = m[0] * gx + m[1] * gy, by = m[1] * gx + m[2] * gy;
      force[2 * j] += bx;
      force[2 * j + 1] += by;
      force[2 * i] -= bx;
      force[2 * i + 1] -= by;
    }
  }
}

void laplacian(const NeighbourList& list, const Geometry& geo, std::span<const double> a,
               std::span<double> lap) {
  const int n = static_cast<int>(list.particles());
  const int* off = list.offsets().data();
  const int* nb = list.neighbours().data();
  const double* v = geo.volume.data();
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
  for (int i = 0; i < n; ++i) {
    double s = v[i] * w0;
    for (int k = off[i]; k < off[i + 1]; ++k) s += v[nb[k]] * geo.w[k];
    out[i] = s;
  }
}

}  // namespace rockcut::fluid::sp
