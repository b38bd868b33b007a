// The operators of a fluid step as precomputed per-pair coefficients (paper eqs. 17, 20 and the
// adjoint pressure force of sp/operators.hpp).
//
// Between two geometry updates (SpParams::geometry_refresh) the SP geometry is fixed, and so the
// step is a fixed sparse linear map. Its per-pair coefficients are computed once per geometry and
// streamed by the step's two passes, which then need no kernel arithmetic and no gathers of x_j,
// V_j or L_j^{-1}. In a cut the geometry changes about once per 10 exchanges.
//
// Per pair (i, j) of row i, at the same index k as Geometry::neighbours:
//   c_k   = B_ij = -V_j F_ij L_i^{-1} (x_j - x_i)   (eq. 17: div_i = sum_k c_k . (v_j - v_i))
//   lam_k = 2 s_i V_j F_ij                          (eq. 20: lap_i = sum_k lam_k (a_i - a_j))
//   t_k   = B_ji = V_i F_ij L_j^{-1} (x_j - x_i)    (adjoint: F_i = sum_k t_k g_j - g_i C_i)
// with s_i = 1 for the paper's eq. 20 and s_i = 2 / tr L_i for the consistent Laplacian
// (sp/consistent_laplacian.hpp: the same pass, so the choice costs the step nothing),
// and per particle C_i = sum_k c_k, with g = A q the excess pressure times the area it acts on.
// t_k has the bits of c at the mirror slot (row j, neighbour i), so the force is the exact
// negative transpose of the divergence and the adjoint energy identity holds to the rounding of
// the sums, as with the operators.
//
// The coefficients are stored as floats (28 bytes per pair over both passes instead of 48) and
// widened by one cvtps2pd; the passes sum in double. Rounding moves each coefficient by at most
// 2^-24 of itself, far below the ~1e-3 operator error of the reused geometry (docs/model.md).
// Alternatives measured and rejected are listed in docs/performance.md.
//
// The results equal the operators' to that rounding (tests/fluid/step_operator_test.cpp).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sp/geometry.hpp"
#include "sp/params.hpp"

namespace rockcut::fluid::sp {

class StepOperator {
 public:
  explicit StepOperator(LaplacianForm laplacian = LaplacianForm::paper) : laplacian_(laplacian) {}

  /// Computes the coefficients for `geo`.
  void build(const Geometry& geo);
  /// After a local refresh of the geometry (refresh_geometry): recomputes the coefficients of
  /// `rows` (LocalRefresh::coefficient_rows), the only ones that changed. Needs the coefficients of
  /// the geometry's previous version; otherwise builds them all and returns false.
  bool rebuild_rows(const Geometry& geo, const std::vector<int>& rows);

  /// The geometry version the coefficients belong to (Geometry::version).
  std::uint64_t version() const { return version_; }

  /// divergence(geo, vel, div) of sp/operators.hpp.
  void divergence(const Geometry& geo, std::span<const double> vel, std::span<double> div) const;
  /// divergence_laplacian(geo, vel, a, div, lap) of sp/operators.hpp, in one pass.
  void divergence_laplacian(const Geometry& geo, std::span<const double> vel,
                            std::span<const double> a, std::span<double> div,
                            std::span<double> lap) const;
  /// adjoint_pressure_force(geo, area, q, force, work) of sp/operators.hpp, given g_i = A_i q_i
  /// [N/m: Pa times m^2 per m of thickness]. `force` gets 2 values per particle (overwritten).
  void adjoint_force(const Geometry& geo, std::span<const double> area_q,
                     std::span<double> force) const;
  /// Each particle's own block of the undrained stiffness the adjoint force answers a
  /// displacement with, K_ii = sum_k w_k (dDiv_k / du_i)(dDiv_k / du_i)^T with w_k = alpha M A_k
  /// (0 where the pressure is held): 3 values per particle (xx, xy, yy) [Pa]
  /// (sp/self_stiffness.cpp).
  void self_stiffness(const Geometry& geo, std::span<const double> weight,
                      std::span<double> out) const;

 private:
  template <class Rows>
  void build_rows(const Rows& rows, const Geometry& geo);
  /// The rows of divergence(), with the Laplacian of `a` in the same pass when kLap.
  template <bool kLap>
  void divergence_rows(const Geometry& geo, std::span<const double> vel, std::span<const double> a,
                       std::span<double> div, std::span<double> lap) const;

  LaplacianForm laplacian_;    ///< which Laplacian lam_k holds (a setting, not state)
  std::vector<float> c_lam_;   ///< per pair: c_x, c_y, lam
  std::vector<float> t_;       ///< per pair: t_x, t_y
  std::vector<double> c_sum_;  ///< per particle: C_i = sum_k c_k (x, y), of the stored floats
  std::uint64_t version_ = ~std::uint64_t{0};
};

}  // namespace rockcut::fluid::sp
