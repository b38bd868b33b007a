// The fluid step's precomputed per-pair coefficients (sp/step_operator.hpp) against the operators
// they replace in the step (sp/operators.hpp), on the committed random packing with its surfaces
// and on a random field: the same sums in another order, with coefficients rounded to floats.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <omp.h>

#include "fluid/sp_test_support.hpp"
#include "sp/operators.hpp"
#include "sp/step_operator.hpp"

namespace rockcut::fluid::test {
namespace {

struct Fields {
  std::vector<double> u, a, q, area;
  /// area_q_i = A_i q_i, what StepOperator::adjoint_force takes.
  std::vector<double> area_q() const {
    std::vector<double> g(q.size());
    for (std::size_t i = 0; i < q.size(); ++i) g[i] = area[i] * q[i];
    return g;
  }
};

Fields random_fields(std::size_t n, const Particles& p, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Fields f{std::vector<double>(2 * n), std::vector<double>(n), std::vector<double>(n),
           std::vector<double>(n)};
  // A rigid translation of 1 m/s under the random part: the difference form (v_j - v_i) must
  // cancel it exactly, as the operators' does.
  for (std::size_t i = 0; i < n; ++i) {
    f.u[2 * i] = 1.0 + 1e-3 * uni(rng);
    f.u[2 * i + 1] = -0.5 + 1e-3 * uni(rng);
  }
  for (double& v : f.a) v = 2e7 + 1e6 * uni(rng);  // p_hydro at 2000 m plus an excess
  for (double& v : f.q) v = 1e6 * uni(rng);
  for (std::size_t i = 0; i < n; ++i) f.area[i] = std::numbers::pi * p.radius[i] * p.radius[i];
  return f;
}

// Largest |a_k - b_k| over the largest |b_k|.
double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    diff = std::max(diff, std::abs(a[k] - b[k]));
    scale = std::max(scale, std::abs(b[k]));
  }
  return diff / scale;
}

TEST(StepOperator, MatchesTheOperatorsItReplaces) {
  // Tolerance 1e-6 of the largest value. The coefficients are stored as floats, each within
  // 2^-24 = 6e-8 of its double; a result sums ~25 of them times differences taken in double, and
  // the divergence's terms are up to ~100 times its largest value at a surface, so the bound is
  // of order 25 x 6e-8 x 100 = 1.5e-4 with all roundings of one sign and ~5 x 6e-8 x 100 = 3e-5
  // at random signs. Measured: 3e-8 (the largest terms are not where the largest values are).
  // 1e-6 leaves a factor ~30 over that and still fails for a wrong coefficient (a sign, L_i^{-1}
  // for L_j^{-1}, a dropped area), which is off by O(1).
  const Initialised s(random_packing(), 0.0015);
  const std::size_t n = s.particles.size();
  const Fields f = random_fields(n, s.particles, 3);
  sp::StepOperator op;
  op.build(s.geo());
  EXPECT_EQ(op.version(), s.geo().version);

  std::vector<double> div_ref(n), lap_ref(n), force_ref(2 * n), work(3 * n);
  sp::divergence_laplacian(s.geo(), f.u, f.a, div_ref, lap_ref);
  sp::adjoint_pressure_force(s.geo(), f.area, f.q, force_ref, work);

  std::vector<double> div(n), lap(n), div_alone(n), force(2 * n);
  op.divergence_laplacian(s.geo(), f.u, f.a, div, lap);
  op.divergence(s.geo(), f.u, div_alone);
  op.adjoint_force(s.geo(), f.area_q(), force);
  EXPECT_LT(relative_difference(div, div_ref), 1e-6);
  EXPECT_LT(relative_difference(lap, lap_ref), 1e-6);
  EXPECT_LT(relative_difference(force, force_ref), 1e-6);
  EXPECT_EQ(div_alone, div);  // the same sums, bit for bit
}

TEST(StepOperator, ForceIsTheNegativeTransposeOfItsDivergence) {
  // The energy identity of the adjoint form, now between the two precomputed passes:
  // sum_k F_k(q) . u_k = sum_i A_i q_i div_i(u). Tolerance as in adjoint_force_test.cpp: the
  // float coefficients do not loosen it, because the force's coefficient of each pair is the
  // divergence's of the mirror pair, bit for bit, and C_i sums the same floats. (Either one
  // rounded on its own misses by ~5e-5 of the scale here, through the 1 m/s translation.)
  const Initialised s(random_packing(), 0.0015);
  const std::size_t n = s.particles.size();
  const Fields f = random_fields(n, s.particles, 5);
  sp::StepOperator op;
  op.build(s.geo());
  std::vector<double> div(n), force(2 * n);
  op.divergence(s.geo(), f.u, div);
  op.adjoint_force(s.geo(), f.area_q(), force);
  double fluid_work = 0.0, energy = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < 2 * n; ++k) fluid_work += force[k] * f.u[k];
  for (std::size_t i = 0; i < n; ++i) {
    energy += f.area[i] * f.q[i] * div[i];
    scale += std::abs(f.area[i] * f.q[i] * div[i]);
  }
  EXPECT_NEAR(fluid_work, energy, 1e-12 * scale);
}

TEST(StepOperator, GivesTheSameBitsWithOneAndTwoThreads) {
  const Initialised s(random_packing(), 0.0015);
  const std::size_t n = s.particles.size();
  const Fields f = random_fields(n, s.particles, 9);
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    sp::StepOperator op;
    op.build(s.geo());
    std::vector<double> div(n), lap(n), force(2 * n);
    op.divergence_laplacian(s.geo(), f.u, f.a, div, lap);
    op.adjoint_force(s.geo(), f.area_q(), force);
    div.insert(div.end(), lap.begin(), lap.end());
    div.insert(div.end(), force.begin(), force.end());
    return div;
  };
  const std::vector<double> one = run(1), two = run(2);
  omp_set_num_threads(1);
  EXPECT_EQ(one, two);
}

}  // namespace
}  // namespace rockcut::fluid::test
