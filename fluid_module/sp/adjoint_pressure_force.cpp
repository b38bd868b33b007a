// The pore-pressure force on the grains in its adjoint form (paper eq. 21 made energy-consistent,
// docs/model.md): declared in sp/operators.hpp; the gradient form is sp/pressure_force.hpp.
#include "sp/operators.hpp"

#include "sp/vec2.hpp"

namespace rockcut::fluid::sp {

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

}  // namespace rockcut::fluid::sp
