// Each grain's own undrained pore-fluid stiffness (Coupling.fluid_stiffness "self";
// docs/model.md, "The grain's own fluid stiffness between exchanges").
//
// Undrained over a fluid step, the pressure of eq. 14 moves by dp_k = -alpha M d(div u)_k with the
// corrected divergence of eq. 17, div_k = sum_l c_kl . (u_l - u_k), and the adjoint force is its
// negative transpose, F = D^T (A dp) (sp/step_operator.hpp). So the force answers a displacement
// with F = -K u, K = alpha M D^T A D, and grain i's own block is
//   K_ii = alpha M [A_i C_i C_i^T + sum_j A_j B_ji B_ji^T],   C_i = sum_j B_ij,
// summed over i's (symmetric) row with the stored coefficients t_k = B_ji. A drained grain's
// pressure is held at p_hydro and so adds nothing (weight 0); cavitation is not counted, which
// errs on the stiff side, where what the lag does is dissipate. Diffusion over the step is left
// out for the same reason.
#include "sp/step_operator.hpp"

#include "sp/vec2.hpp"

namespace rockcut::fluid::sp {

void StepOperator::self_stiffness(const Geometry& geo, std::span<const double> weight,
                                  std::span<double> out) const {
  const int n = static_cast<int>(geo.particles());
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  const float* t = t_.data();
  const double* cs = c_sum_.data();
  const double* w = weight.data();
  double* k = out.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double cx = cs[2 * i], cy = cs[2 * i + 1];
    double kxx = w[i] * cx * cx, kxy = w[i] * cx * cy, kyy = w[i] * cy * cy;
    for (int q = begin[i]; q < end[i]; ++q) {
      const double wj = w[nb[q]];
      const double tx = t[2 * q], ty = t[2 * q + 1];
      kxx += wj * tx * tx;
      kxy += wj * tx * ty;
      kyy += wj * ty * ty;
    }
    k[3 * i] = kxx;
    k[3 * i + 1] = kxy;
    k[3 * i + 2] = kyy;
  }
}

}  // namespace rockcut::fluid::sp
