// The consistent (renormalised) SP Laplacian, fluid.laplacian "consistent": the Brookshaw /
// Cleary & Monaghan sum of eq. 20 divided by its own second moment, so that inside a packing it
// reproduces the Laplacian of a quadratic field to the first-moment noise (Chen, Beraun & Carney 1999, "A corrective
// smoothed particle method for boundary value problems in heat conduction", IJNME 46:231-252: the
// CSPM normalisation of second derivatives; Schwaiger 2008, "An implicit corrected SPH
// formulation for thermal diffusion with linear free surface boundary conditions", IJNME
// 75:647-671, in its isotropic, trace form; compared in Korzilius, Schilders & Anthonissen 2017,
// J. Appl. Math. Phys. 5:168-184):
//
//   lap a_i = s_i sum_j 2 V_j (a_i - a_j) F_ij,   s_i = d / tr L_i,   d = 2,
//   tr L_i  = sum_j V_j (-F_ij) r_ij^2   (the trace of the CSPM matrix of eq. 16).
//
// Why: eq. 20 applied to a quadratic gives 2 tr L_i / d times its Laplacian. In the continuum
// tr L = d, but on a random packing at the paper's h (2.5 spacings) the discrete second moment
// falls short by about 5 % (tr L = 1.9), and every diffusion on eq. 20 runs at about 0.95 D
// (docs/verification.md).
//
// What it keeps: V~_i lap a_i = sum_j w_ij (a_j - a_i) with the symmetric weights of eq. 20,
// w_ij = -2 V_i V_j F_ij >= 0, and the renormalised volume V~_i = V_i / s_i. So the operator
// conserves sum_i V~_i a_i, dissipates sum_i V~_i a_i^2 (explicit and implicit steps stay stable,
// the implicit matrix symmetric positive definite), and keeps eq. 20's natural no-flux condition
// at free surfaces. It leaves the strain rate (eq. 17) and the adjoint force untouched, so the
// coupled energy identity (sp/operators.hpp) holds as before.
//
// The cap: s_i <= kMaxLaplacianScale = 1.1. The renormalisation corrects the kernel quadrature's
// deficit of the second moment inside the packing (tr L = 1.9, s = 1.05 on the random packing at
// h = 2.5 spacings; lattice sums: 6 % at h = 2 spacings), not the half support of a surface
// particle (tr L ~ 1). There the missing half is eq. 20's natural no-flux condition, and scaling
// its row by 2 / tr L made diffusion along the Terzaghi column's sealed sides twice too fast
// (measured error 5 % at T_v = 0.2, 25 % at T_v = 1, against 0.8 % and 1.9 % with the cap) and
// raised the explicit step's spectral radius by 1.7 (C_crit 0.032-0.08 instead of 0.063-0.093).
// With the cap, surface and corner rows get at most the interior's correction, and the smallest
// measured C_crit is 0.058 (tests/fluid/laplacian_stability_test.cpp), and the explicit model
// keeps C = 0.05.
#pragma once

#include <span>

#include "sp/geometry.hpp"

namespace rockcut::fluid::sp {

/// The largest renormalisation s_i (see the cap above).
inline constexpr double kMaxLaplacianScale = 1.1;

/// s_i = 2 / tr L_i, at most kMaxLaplacianScale (so also where tr L_i = 0: a particle alone,
/// whose Laplacian is zero anyway).
inline double consistent_laplacian_scale(double l_trace) {
  return l_trace * kMaxLaplacianScale > 2.0 ? 2.0 / l_trace : kMaxLaplacianScale;
}

/// lap a_i = s_i sum_j 2 V_j (a_i - a_j) F_ij (see above). The models' step applies it through
/// sp/step_operator.hpp; this is its definition, checked against closed forms in tests/fluid/.
void consistent_laplacian(const Geometry& geo, std::span<const double> a, std::span<double> lap);

}  // namespace rockcut::fluid::sp
