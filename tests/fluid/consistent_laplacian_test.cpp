// The consistent (renormalised) Laplacian of sp/consistent_laplacian.hpp against eq. 20: unbiased
// for a quadratic field on a random packing, exact on a lattice, and the same operator in the step
// coefficients. Its conservation, the explicit constant C and both models with it:
// laplacian_stability_test.cpp (BothLaplacians, ExplicitStability).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "fluid/sp_test_support.hpp"
#include "sp/consistent_laplacian.hpp"
#include "sp/operators.hpp"
#include "sp/step_operator.hpp"

namespace rockcut::fluid::test {
namespace {

using sp::LaplacianForm;

// Mean of lap(x^2 + y^2) / 4 over the particles at least h from the packing's bounding box.
double quadratic_ratio(LaplacianForm form, const Initialised& init, double h) {
  const std::size_t n = init.particles.size();
  std::vector<double> a(n), lap(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = init.particles.x(i), y = init.particles.y(i);
    a[i] = x * x + y * y;
  }
  apply_laplacian(form, init.geo(), a, lap);
  const std::vector<double> d = distance_to_box(init.particles);
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (d[i] < h) continue;
    sum += lap[i] / 4.0;
    ++count;
  }
  return sum / count;
}

TEST(ConsistentLaplacian, IsUnbiasedForAQuadraticFieldInsideARandomPacking) {
  // lap (x^2 + y^2) = 4. On the committed random packing at the paper's h (1.5 mm, about 2.5
  // spacings) eq. 20 gives on average 2 tr L / d of it; the renormalisation divides that out.
  // Measured mean over the particles at least h inside: eq. 20 0.950, consistent 0.990 (with
  // the cap at 1.1; 0.985 at a cap of 1.05). What remains is the first-moment term
  // 4 x_i . sum_j V_j F_ij (x_j - x_i) of the disordered rows. 1.5 % leaves room for it and fails
  // for the uncorrected operator; eq. 20's bias is asserted too, so that the test shows what the
  // correction corrects.
  const double h = 0.0015;
  const Initialised init(random_packing(), h);
  const double paper = quadratic_ratio(LaplacianForm::paper, init, h);
  const double consistent = quadratic_ratio(LaplacianForm::consistent, init, h);
  std::printf("mean lap(r^2) / 4 inside: eq. 20 %.4f, consistent %.4f\n", paper, consistent);
  EXPECT_NEAR(consistent, 1.0, 0.015);
  EXPECT_LT(paper, 0.97);
}

TEST(ConsistentLaplacian, IsExactForAQuadraticFieldInsideALattice) {
  // On a lattice the first moment vanishes inside, so the renormalised sum is exact for any h,
  // where eq. 20 has the quadrature error of ConvergesOnALatticeAsTheKernelCoversMoreParticles
  // (-5.9 % at h = 2 spacings). Round-off only: 1e-9.
  const double s = 0.001;
  for (double ratio : {2.0, 2.5, 3.0}) {
    const Initialised init(lattice(36, 36, s, 0.4e-3), ratio * s);
    std::vector<double> a(init.particles.size()), lap(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double x = init.particles.x(i) - 0.0175, y = init.particles.y(i) - 0.0175;
      a[i] = x * x + y * y;
    }
    sp::consistent_laplacian(init.geo(), a, lap);
    EXPECT_NEAR(lap[18 * 36 + 18] / 4.0, 1.0, 1e-9) << "h / spacing = " << ratio;
  }
}

TEST(ConsistentLaplacian, TheStepCoefficientsApplyTheSameOperator) {
  // StepOperator's lam_k = 2 s_i V_j F_ij (floats): its Laplacian equals the operator's to the
  // float rounding of the coefficients (6e-8 of each term; the sum's terms cancel to about 1e-3 of
  // their magnitude for a smooth field, so 1e-4 of the largest |lap|).
  const Initialised init(random_packing(), 0.0015);
  const std::size_t n = init.particles.size();
  std::vector<double> a(n), vel(2 * n, 0.0), div(n), lap(n), ref(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = init.particles.x(i), y = init.particles.y(i);
    a[i] = 1e5 * std::exp(-(x * x + y * y) / (2.0 * 0.004 * 0.004));
  }
  sp::StepOperator op(LaplacianForm::consistent);
  op.build(init.geo());
  op.divergence_laplacian(init.geo(), vel, a, div, lap);
  sp::consistent_laplacian(init.geo(), a, ref);
  double largest = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    largest = std::max(largest, std::abs(ref[i]));
    diff = std::max(diff, std::abs(lap[i] - ref[i]));
  }
  EXPECT_LT(diff, 1e-4 * largest);
}

}  // namespace
}  // namespace rockcut::fluid::test
