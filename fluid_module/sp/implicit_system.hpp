// The backward-Euler step of the pore-pressure equation (eq. 14) as one sparse symmetric positive
// definite system, solved by preconditioned conjugate gradients (Eigen).
//
// With the eq. 20 Laplacian, V_i dp_i/dt = D sum_j w_ij (p_j - p_i) + V_i s_i, with symmetric
// weights w_ij = -2 V_i V_j F_ij >= 0 and the source s_i = -alpha M (volumetric strain rate)_i.
// Backward Euler for the increment d = p^{n+1} - p^n:
//   (V_i + dt D sum_j w_ij) d_i - dt D sum_j w_ij d_j = dt (V_i s_i - D sum_j w_ij (p^n_i - p^n_j)),
// a weighted graph Laplacian plus a positive diagonal: symmetric positive definite, unconditionally
// stable. Solving for the increment (not the absolute pressure, which is ~1e5 Pa even when nothing
// happens) makes the relative tolerance a tolerance on the change of the step.
//
// With the consistent Laplacian (sp/consistent_laplacian.hpp) V_i on the left becomes the
// renormalised volume V~_i = V_i / s_i: the weights stay those of eq. 20, so the matrix stays
// symmetric positive definite.
//
// Fixed particles (drained: p = p_hydro; cavitated: p = p_min) become identity rows and their
// columns move to the right-hand side, which keeps the matrix symmetric.
//
// Cavitation (eq. 22) in the implicit step is the constraint p >= p_min with a vapour source that
// is active only while the particle is clamped, the backward-Euler form of "dp/dt = max(dp/dt, 0)
// at p = p_min". It is solved by a primal-dual active set: clamp the particles that the solve
// takes below p_min, release clamped particles whose unconstrained equation would raise them
// (positive residual), and repeat until the set no longer changes (docs/model.md).
//
// Memory: the matrix pattern (the geometry's pairs inside the support) is rebuilt only when the
// geometry is recomputed; each step writes its values in place. Eigen's conjugate gradient
// allocates its four work vectors once per solve (per step, never per particle).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include "sp/boundary.hpp"
#include "sp/geometry.hpp"
#include "sp/params.hpp"

namespace rockcut::fluid::sp {

struct ImplicitReport {
  unsigned iterations = 0;  ///< conjugate-gradient iterations, summed over the active-set rounds
  unsigned rounds = 0;      ///< active-set rounds (1 without cavitation changes)
  std::size_t clamped = 0;  ///< particles held at p_min after the step
};

class ImplicitSystem {
 public:
  ImplicitSystem(double tolerance, unsigned max_iterations,
                 LaplacianForm laplacian = LaplacianForm::paper);

  /// Advances `p` [Pa] by dt [s]: D [m^2/s], `source` [Pa/s] per particle. Throws
  /// std::runtime_error if the solver does not converge.
  ImplicitReport step(double dt_s, double diffusivity_m2_s, const Geometry& geo,
                      std::span<const double> source,
                      std::span<const Boundary> boundary, double p_hydro_pa, bool cavitation,
                      double p_min_pa, std::span<double> p);

  /// Largest number of active-set rounds per step; after it the pressure is clamped at p_min.
  static constexpr unsigned kMaxRounds = 50;

  /// The conjugate-gradient start of the next step (the last increment): a checkpoint keeps it,
  /// since the solution's last bits depend on where the iteration starts.
  std::vector<double> guess() const { return {guess_.data(), guess_.data() + guess_.size()}; }
  void set_guess(std::span<const double> guess);

 private:
  enum Fixed : std::uint8_t { free = 0, drained = 1, clamped = 2 };
  void rebuild_pattern(const Geometry& geo);
  void assemble(double dt_s, double d_m2_s, const Geometry& geo, std::span<const double> source,
                std::span<const double> p);
  /// b_i - (A d)_i of particle i's unconstrained equation (positive: it would rise).
  double free_residual(int i, double dt_s, double d_m2_s, const Geometry& geo,
                       std::span<const double> source, std::span<const double> p) const;

  /// The mass of row i: V_i, or V~_i = V_i / s_i for the consistent Laplacian.
  double mass(const Geometry& geo, int i) const;

  double tolerance_;
  unsigned max_iterations_;
  LaplacianForm laplacian_;
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> a_;
  std::vector<int> diagonal_;   // index of A_ii in the values
  std::vector<int> row_start_;  // value index of the geometry's pair k of row i: row_start_[i] + k
  std::uint64_t pattern_of_geometry_ = static_cast<std::uint64_t>(-1);  // Geometry::version
  Eigen::VectorXd b_, d_, guess_;
  std::vector<Fixed> fixed_;
  std::vector<double> fixed_value_;  // the increment of a fixed particle
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double, Eigen::RowMajor, int>,
                           Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>>
      cg_;
};

}  // namespace rockcut::fluid::sp
