// The consistent (renormalised) Laplacian of sp/consistent_laplacian.hpp against eq. 20: unbiased
// for a quadratic field on a random packing, conservative in the renormalised volumes, as stable as
// eq. 20 under the explicit model's constant, and the same operator in the step coefficients and
// in both models.
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

void apply(LaplacianForm form, const sp::Geometry& geo, std::span<const double> a,
           std::span<double> lap) {
  if (form == LaplacianForm::consistent) {
    sp::consistent_laplacian(geo, a, lap);
  } else {
    sp::laplacian(geo, a, lap);
  }
}

// The volume in which the operator is symmetric: V_i (eq. 20) or V_i / s_i (consistent).
double weight(LaplacianForm form, const sp::Geometry& geo, std::size_t i) {
  return form == LaplacianForm::paper
             ? geo.volume[i]
             : geo.volume[i] / sp::consistent_laplacian_scale(geo.l_trace[i]);
}

// Mean of lap(x^2 + y^2) / 4 over the particles at least h from the packing's bounding box.
double quadratic_ratio(LaplacianForm form, const Initialised& init, double h) {
  const std::size_t n = init.particles.size();
  std::vector<double> a(n), lap(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = init.particles.x(i), y = init.particles.y(i);
    a[i] = x * x + y * y;
  }
  apply(form, init.geo(), a, lap);
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

TEST(ConsistentLaplacian, ConservesTheRenormalisedVolumeIntegral) {
  // sum_i V~_i lap a_i = sum_ij w_ij (a_j - a_i) = 0 for any a (V~ = V / s): no flux leaves a free
  // surface, as with eq. 20. Round-off relative to sum_i V~_i |lap a_i|.
  const Initialised init(random_packing(), 0.0015);
  const std::size_t n = init.particles.size();
  std::vector<double> a(n), lap(n);
  std::mt19937_64 rng(11);
  for (double& v : a) v = 1e5 + static_cast<double>(rng() >> 11) * 0x1.0p-53 * 1e4;
  sp::consistent_laplacian(init.geo(), a, lap);
  double sum = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = weight(LaplacianForm::consistent, init.geo(), i);
    sum += w * lap[i];
    scale += w * std::abs(lap[i]);
  }
  EXPECT_LT(std::abs(sum) / scale, 1e-12);
}

// Spectral radius by power iteration in the operator's own inner product (where it is symmetric
// negative semi-definite), as in laplacian_stability_test.cpp.
double spectral_radius(LaplacianForm form, const Initialised& init) {
  const std::size_t n = init.particles.size();
  std::vector<double> x(n), y(n), w(n);
  for (std::size_t i = 0; i < n; ++i) w[i] = weight(form, init.geo(), i);
  std::mt19937_64 rng(5);
  for (double& v : x) v = (rng() & 1) ? 1.0 : -1.0;
  double rho = 0.0;
  for (int it = 0; it < 500; ++it) {
    apply(form, init.geo(), x, y);
    double xy = 0.0, xx = 0.0, yy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      xy += w[i] * x[i] * y[i];
      xx += w[i] * x[i] * x[i];
      yy += w[i] * y[i] * y[i];
    }
    rho = std::abs(xy) / xx;
    const double norm = std::sqrt(yy);
    for (std::size_t i = 0; i < n; ++i) x[i] = y[i] / norm;
  }
  return rho;
}

TEST(ConsistentLaplacian, TheExplicitConstantCStaysBelowItsMeasuredCriticalValues) {
  // The explicit model keeps dt <= C h^2 / D with C = 0.05 for both Laplacians. The renormalised
  // rows are larger by s_i <= 1.1, so its spectral radius is measured on the cases of
  // TheConstantCIsBelowEveryMeasuredCriticalValue. Measured C_crit: 0.058-0.088 (eq. 20:
  // 0.063-0.093), the smallest at the largest h / spacing, as for eq. 20; C = 0.05 stays 13 %
  // below it. Asserted: at least 10 % (a cap of 1.2 would fail it: 0.053).
  const double s = 0.0006;
  struct Case {
    const char* name;
    Particles p;
    double h;
  };
  const std::vector<Case> cases = {
      {"lattice h/s 2", lattice(30, 30, s, 2.5e-4), 2.0 * s},
      {"lattice h/s 2.5", lattice(30, 30, s, 2.5e-4), 2.5 * s},
      {"lattice h/s 5", lattice(30, 30, s, 2.5e-4), 5.0 * s},
      {"jittered h/s 2.5", jittered(30, 30, s, 0.3, 1), 2.5 * s},
      {"jittered h/s 4", jittered(30, 30, s, 0.3, 2), 4.0 * s},
      {"random h 1.5 mm", random_packing(), 0.0015},
      {"random h 3 mm", random_packing(), 0.003},
  };
  for (const Case& c : cases) {
    const Initialised init(c.p, c.h);
    const double paper = 2.0 / (spectral_radius(LaplacianForm::paper, init) * c.h * c.h);
    const double consistent =
        2.0 / (spectral_radius(LaplacianForm::consistent, init) * c.h * c.h);
    std::printf("%-18s C_crit eq. 20 %.4f, consistent %.4f\n", c.name, paper, consistent);
    EXPECT_LE(sp::kExplicitStabilityC, 0.9 * consistent) << c.name;
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

sp::SpParams consistent_pulse(double h) {
  sp::SpParams s = table1(h);
  s.laplacian = LaplacianForm::consistent;
  s.pulse_amplitude_pa = 1e5;
  s.pulse_sigma_m = 0.003;
  return s;
}

TEST(ConsistentLaplacian, ImplicitAndExplicitModelsAgreeAtSmallStepsAndTheImplicitOneIsStable) {
  // The same semi-discrete system under forward and backward Euler (bound 9e-3 as in
  // ImplicitStability.AgreesWithTheExplicitModelAtSmallSteps); then the implicit model at 100
  // times the explicit limit keeps the renormalised energy sum V~ q^2 and the maximum from growing.
  const sp::SpParams params = consistent_pulse(0.0015);
  sp::ExplicitModel ex(params);
  sp::ImplicitModel im(params);
  Driver de(ex, random_packing()), di(im, random_packing());
  const double dt = 0.5 * ex.dt_max_s();
  for (int k = 0; k < 80; ++k) {
    de.step(dt);
    di.step(dt);
  }
  double diff = 0.0, amp = 0.0;
  for (std::size_t i = 0; i < ex.pressure().size(); ++i) {
    diff = std::max(diff, std::abs(ex.pressure()[i] - im.pressure()[i]));
    amp = std::max(amp, ex.pressure()[i] - params.p_hydro_pa);
  }
  EXPECT_LT(diff / amp, 1e-2);
  EXPECT_GT(diff / amp, 1e-6);

  sp::ImplicitModel big(params);
  Driver db(big, random_packing());
  double previous_max = 1e5, previous_energy = INFINITY;
  for (int k = 0; k < 20; ++k) {
    db.step(100.0 * ex.dt_max_s());
    double mx = -INFINITY, energy = 0.0;
    for (std::size_t i = 0; i < big.pressure().size(); ++i) {
      const double e = big.pressure()[i] - params.p_hydro_pa;
      ASSERT_TRUE(std::isfinite(e));
      mx = std::max(mx, e);
      energy += weight(LaplacianForm::consistent, big.geometry(), i) * e * e;
    }
    EXPECT_LE(mx, previous_max * (1 + 1e-9)) << "step " << k;
    EXPECT_LE(energy, previous_energy * (1 + 1e-9)) << "step " << k;
    previous_max = mx;
    previous_energy = energy;
  }
}

}  // namespace
}  // namespace rockcut::fluid::test
