// The SP operators on a Geometry (paper section 3.2). Each is one streaming pass over the pairs
// inside the support (the geometry's rows) that writes one value per particle (rows are
// independent: no atomics would be needed to split them between threads).
//
// Definitions: cspm_gradient.cpp (eq. 16), divergence_laplacian.cpp (eqs. 17 and 20),
// adjoint_pressure_force.cpp (eq. 21, adjoint form) and cspm_interpolation.cpp (eq. 15).
// These are the operators' definitions, checked against closed forms (tests/fluid/). The models'
// step applies the divergence, the Laplacian and the adjoint force through sp/step_operator.hpp,
// the same sums with their per-pair coefficients computed once per geometry and checked against
// these; `gradient` serves the gradient force form (fluid.force_form "gradient") directly.
#pragma once

#include <span>

#include "sp/geometry.hpp"

namespace rockcut::fluid::sp {

/// CSPM gradient (eq. 16 in its 2x2 matrix form, Chen et al. 1999):
///   grad a_i = L_i^{-1} sum_j V_j (a_j - a_i) grad_i W_ij.
/// Exact for linear fields wherever L_i is well conditioned (inside and at surfaces).
/// `grad` gets 2 values per particle.
void gradient(const Geometry& geo, std::span<const double> a, std::span<double> grad);

/// Corrected divergence of a vector field (eq. 17): the trace of the CSPM velocity gradient
///   (grad v)_i = [sum_j V_j (v_j - v_i) (x) grad_i W_ij] L_i^{-1}.
/// `v` has 2 values per particle. Exact for linear fields.
void divergence(const Geometry& geo, std::span<const double> v, std::span<double> div);

/// The pore-pressure force that is the negative adjoint of `divergence` (energy-consistent):
///   F_k = sum_i A_i q_i B_ik - A_k q_k sum_j B_kj,   B_ij = V_j L_i^{-1} grad_i W_ij,
/// with q the excess pressure and A_i the area it acts on (pi r_i^2). It is -dE/du_k of the
/// stored energy E = sum_i A_i q_i^2 / (2 alpha M) when q_i = -alpha M div_i(u): the coupled
/// DEM-fluid system then conserves E plus the grains' energy (diffusion, drainage and the
/// cavitation clamp only take energy out). Inside, it approximates -A_k grad q_k (the symmetric
/// SPH form); its forces sum to zero. `force` gets 2 values per particle (overwritten); `work`
/// is scratch of 3 values per particle (A_i q_i L_i^{-1}).
void adjoint_pressure_force(const Geometry& geo, std::span<const double> area,
                            std::span<const double> q, std::span<double> force,
                            std::span<double> work);

/// The Cleary & Monaghan (Brookshaw) Laplacian of eq. 20 for a uniform coefficient, with the SP
/// volume V_j in place of m_j / rho_i:
///   lap a_i = sum_j 2 V_j (a_i - a_j) F_ij,   F_ij = (n_ij . grad_i W_ij) / r_ij.
/// Conservative (sum_i V_i lap a_i = 0 for any a), hence the natural no-flux condition at free
/// surfaces (section 3.3).
void laplacian(const Geometry& geo, std::span<const double> a, std::span<double> lap);

/// divergence(vel) into `div` and laplacian(a) into `lap` in one pass over the pairs, with the
/// same bits as the two calls (the explicit model's step needs both on the same geometry).
void divergence_laplacian(const Geometry& geo, std::span<const double> vel,
                          std::span<const double> a, std::span<double> div,
                          std::span<double> lap);

/// CSPM interpolation (eq. 15) with the first-order term of Chen et al. (1999):
///   a*_i = [sum_j V_j a_j W_ij - grad a_i . sum_j V_j (x_j - x_i) W_ij] / sum_j V_j W_ij,
/// j including i. Exact for linear fields when `grad` is their CSPM gradient.
void interpolate(const Geometry& geo, double w0,
                 std::span<const double> a, std::span<const double> grad,
                 std::span<double> out);

/// sum_j V_j W_ij including the self term V_i W(0): the partition of unity, ~1 inside.
void volume_sum(const Geometry& geo, double w0, std::span<double> out);

}  // namespace rockcut::fluid::sp
