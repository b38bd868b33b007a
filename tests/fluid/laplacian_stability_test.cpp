// The eq. 20 Laplacian (conservation, consistency on lattices) and the explicit model's stability
// constant C of dt <= C h^2 / D, found here by measurement; the explicit model's refusal above its
// limit and the implicit model's stability far above it.
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <random>

#include "fluid/sp_test_support.hpp"
#include "sp/consistent_laplacian.hpp"
#include "sp/operators.hpp"

namespace rockcut::fluid::sp {
// The parameter's name in the test names (gtest finds it by argument-dependent lookup).
inline void PrintTo(LaplacianForm form, std::ostream* os) {
  *os << (form == LaplacianForm::paper ? "paper" : "consistent");
}
}  // namespace rockcut::fluid::sp

namespace rockcut::fluid::test {
namespace {

// Both Laplacians (fluid.laplacian): the consistent one has eq. 20's weights over the volumes
// V~ = V / s (sp/consistent_laplacian.hpp), the same kind of matrix.
class BothLaplacians : public testing::TestWithParam<sp::LaplacianForm> {
 protected:
  sp::SpParams params() const {
    sp::SpParams s = table1(0.0015);
    s.pulse_amplitude_pa = 1e5;
    s.pulse_sigma_m = 0.003;
    s.laplacian = GetParam();
    return s;
  }
  // The volume in which the operator is symmetric and its energy falls.
  static double weight(const sp::Geometry& geo, std::size_t i) {
    return laplacian_weight(GetParam(), geo, i);
  }
};

TEST_P(BothLaplacians, ConserveTheVolumeIntegralOnARandomPacking) {
  // sum_i V_i lap a_i = sum_ij 2 V_i V_j F_ij (a_i - a_j) = 0 by antisymmetry, for any a: no flux
  // leaves through a free surface (section 3.3); for the consistent Laplacian with V~ = V / s.
  // Round-off: relative to sum_i V_i |lap a_i|.
  const Initialised init(random_packing(), 0.0015);
  const std::size_t n = init.particles.size();
  std::vector<double> a(n), lap(n);
  std::mt19937_64 rng(11);
  for (double& v : a) v = 1e5 + static_cast<double>(rng() >> 11) * 0x1.0p-53 * 1e4;
  apply_laplacian(GetParam(), init.geo(), a, lap);
  double sum = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += weight(init.geo(), i) * lap[i];
    scale += weight(init.geo(), i) * std::abs(lap[i]);
  }
  EXPECT_LT(std::abs(sum) / scale, 1e-12);
}

TEST(Laplacian, ConvergesOnALatticeAsTheKernelCoversMoreParticles) {
  // lap (x^2 + y^2) = 4. Inside a lattice the eq. 20 sum with V = 1 / sum W equals
  // 4 sum(r^2 F / 2) / sum W: a kernel quadrature whose error falls quickly with h / spacing
  // (lattice sums: -5.9 % at 2, -0.8 % at 3, -0.2 % at 4, -0.04 % at 5).
  const double s = 0.001;
  double previous = 1.0;
  for (double ratio : {2.0, 3.0, 4.0, 5.0}) {
    const Initialised init(lattice(36, 36, s, 0.4e-3), ratio * s);
    std::vector<double> a(init.particles.size()), lap(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double x = init.particles.x(i) - 0.0175, y = init.particles.y(i) - 0.0175;
      a[i] = x * x + y * y;
    }
    sp::laplacian(init.geo(), a, lap);
    const double centre = lap[18 * 36 + 18];
    const double error = std::abs(centre / 4.0 - 1.0);
    EXPECT_LT(error, previous) << "h / spacing = " << ratio;
    previous = error;
  }
  EXPECT_LT(previous, 1e-3);
}

// Spectral radius of the Laplacian [1/m^2] by power iteration with the Rayleigh quotient in the
// V-weighted (consistent: V~-weighted) inner product, in which the operator is symmetric. The quotient approaches the
// radius from below, so C_crit = 2 / (rho h^2) is approached from above; 500 iterations give the
// same 3 digits as 3000 here, and agree within 1 % with a Lanczos eigensolver (scipy eigsh on the
// same operator, when the constant was chosen).
double spectral_radius(const Initialised& init,
                       sp::LaplacianForm form = sp::LaplacianForm::paper) {
  const std::size_t n = init.particles.size();
  std::vector<double> x(n), y(n), V(n);
  std::mt19937_64 rng(5);
  for (double& v : x) v = (rng() & 1) ? 1.0 : -1.0;
  for (std::size_t i = 0; i < n; ++i) V[i] = laplacian_weight(form, init.geo(), i);
  double rho = 0.0;
  for (int it = 0; it < 500; ++it) {
    apply_laplacian(form, init.geo(), x, y);
    double xy = 0.0, xx = 0.0, yy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      xy += V[i] * x[i] * y[i];
      xx += V[i] * x[i] * x[i];
      yy += V[i] * y[i] * y[i];
    }
    rho = std::abs(xy) / xx;
    const double norm = std::sqrt(yy);
    for (std::size_t i = 0; i < n; ++i) x[i] = y[i] / norm;
  }
  return rho;
}

// Forward Euler x <- x + dt lap x (D = 1) from a random start: the largest |x| after `steps`.
double euler_growth(const Initialised& init, double dt, int steps) {
  const std::size_t n = init.particles.size();
  std::vector<double> x(n), lap(n);
  std::mt19937_64 rng(9);
  for (double& v : x) v = (rng() & 1) ? 1.0 : -1.0;
  for (int k = 0; k < steps; ++k) {
    sp::laplacian(init.geo(), x, lap);
    for (std::size_t i = 0; i < n; ++i) x[i] += dt * lap[i];
  }
  double m = 0.0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}

TEST(ExplicitStability, TheConstantCIsBelowEveryMeasuredCriticalValue) {
  struct Case {
    const char* name;
    Particles p;
    double h;
  };
  const double s = 0.0006;
  const std::vector<Case> cases = {
      {"lattice h/s 2", lattice(30, 30, s, 2.5e-4), 2.0 * s},
      {"lattice h/s 2.5", lattice(30, 30, s, 2.5e-4), 2.5 * s},
      {"lattice h/s 3", lattice(30, 30, s, 2.5e-4), 3.0 * s},
      {"lattice h/s 5", lattice(30, 30, s, 2.5e-4), 5.0 * s},
      {"jittered h/s 2.5", jittered(30, 30, s, 0.3, 1), 2.5 * s},
      {"jittered h/s 4", jittered(30, 30, s, 0.3, 2), 4.0 * s},
      {"random h 1.5 mm", random_packing(), 0.0015},
      {"random h 3 mm", random_packing(), 0.003},
  };
  double smallest = 1.0;
  for (const Case& c : cases) {
    const Initialised init(c.p, c.h);
    const double rho = spectral_radius(init);
    const double c_crit = 2.0 / (rho * c.h * c.h);
    const double c_consistent =
        2.0 / (spectral_radius(init, sp::LaplacianForm::consistent) * c.h * c.h);
    std::printf("%-18s C_crit = %.4f (consistent %.4f)\n", c.name, c_crit, c_consistent);
    smallest = std::min(smallest, c_crit);
    // C must leave a margin of at least 15 % below every measured critical value of eq. 20.
    EXPECT_LE(sp::kExplicitStabilityC, 0.85 * c_crit) << c.name;
    // The consistent Laplacian's rows are larger by s_i <= 1.1 (sp/consistent_laplacian.hpp):
    // measured 0.058-0.088 against eq. 20's 0.063-0.093, C = 0.05 stays 13 % below the smallest;
    // at least 10 % is asserted (a cap of 1.2 would fail it: 0.053).
    EXPECT_LE(sp::kExplicitStabilityC, 0.9 * c_consistent) << c.name;
  }
  // And it is not needlessly small: the smallest measured value is within 1.5x of C.
  EXPECT_LT(smallest, 1.5 * sp::kExplicitStabilityC);
}

TEST(ExplicitStability, ForwardEulerGrowsJustAboveTheMeasuredLimitAndNotJustBelow) {
  // The measured limit is the real one: 5 % above it the highest mode grows like 1.05^steps.
  const Initialised init(random_packing(), 0.0015);
  const double dt_crit = 2.0 / spectral_radius(init);
  EXPECT_LT(euler_growth(init, 0.95 * dt_crit, 600), 1.0);
  EXPECT_GT(euler_growth(init, 1.05 * dt_crit, 600), 1e6);
}

sp::SpParams pulse_params(double h) {
  sp::SpParams s = table1(h);
  s.pulse_amplitude_pa = 1e5;
  s.pulse_sigma_m = 0.003;
  return s;
}

TEST(ExplicitStability, TheModelRefusesAStepAboveItsLimitWithAClearMessage) {
  sp::ExplicitModel model(pulse_params(0.0015));
  Driver drive(model, random_packing());
  const double limit = model.dt_max_s();
  EXPECT_NEAR(limit, 0.05 * 0.0015 * 0.0015 / 0.02, 1e-18);  // C h^2 / D, D = 2e9 * 1e-14 / 1e-3
  ASSERT_EQ(model.limits().size(), 1u);
  EXPECT_EQ(model.limits()[0].dt_max_s, limit);
  drive.step(limit);  // at the limit: accepted
  const std::vector<double> before(model.pressure().begin(), model.pressure().end());
  try {
    drive.step(1.5 * limit);
    FAIL() << "a step 1.5x above the limit was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("exceeds the stability limit"), std::string::npos) << m;
    EXPECT_NE(m.find("by 1.5x"), std::string::npos) << m;
    EXPECT_NE(m.find("implicit"), std::string::npos) << m;  // says what to change
  }
  // Refused before anything changed.
  EXPECT_EQ(std::vector<double>(model.pressure().begin(), model.pressure().end()), before);
}

TEST_P(BothLaplacians, ImplicitStaysStableAtOneHundredTimesTheExplicitLimit) {
  // Backward Euler with the eq. 20 matrix (an M-matrix) is unconditionally stable and keeps the
  // maximum principle: the excess pressure of a positive pulse stays in [0, its initial maximum],
  // its maximum and its V-weighted energy (V~ for the consistent Laplacian) never grow.
  const sp::SpParams params = this->params();
  sp::ImplicitModel model(params);
  Driver drive(model, random_packing());
  const double dt = 100.0 * sp::ExplicitModel(params).dt_max_s();
  double previous_max = 1e5, previous_energy = INFINITY;
  for (int k = 0; k < 20; ++k) {
    drive.step(dt);
    double mx = -INFINITY, mn = INFINITY, energy = 0.0;
    for (std::size_t i = 0; i < model.pressure().size(); ++i) {
      const double e = model.pressure()[i] - params.p_hydro_pa;
      ASSERT_TRUE(std::isfinite(e));
      mx = std::max(mx, e);
      mn = std::min(mn, e);
      energy += weight(model.geometry(), i) * e * e;
    }
    EXPECT_LE(mx, previous_max * (1 + 1e-9)) << "step " << k;
    EXPECT_LE(energy, previous_energy * (1 + 1e-9)) << "step " << k;
    EXPECT_GE(mn, -1e-6 * 1e5) << "step " << k;  // solver tolerance 1e-8 of the step's change
    previous_max = mx;
    previous_energy = energy;
  }
  EXPECT_LT(previous_max, 1e3);  // 20 steps of 0.56 ms: the pulse has drained away
  EXPECT_GT(model.last_solve().iterations, 0u);
}

TEST_P(BothLaplacians, ImplicitAgreesWithTheExplicitModelAtSmallSteps) {
  // Two integrators of the same semi-discrete system: forward and backward Euler err by
  // -+ n (lambda dt)^2 / 2 e^{-lambda t} on a mode of rate lambda, so they differ by at most
  // 2 lambda dt / e of the amplitude. At the pulse's peak lambda = 2 D / sigma^2 = 4400 1/s, and
  // with dt = half the explicit limit (2.8e-6 s) the bound is 9e-3 (measured: 5.9e-3).
  const sp::SpParams params = this->params();
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
  EXPECT_GT(diff / amp, 1e-6);  // they are different schemes
}

INSTANTIATE_TEST_SUITE_P(Form, BothLaplacians,
                         testing::Values(sp::LaplacianForm::paper, sp::LaplacianForm::consistent),
                         [](const testing::TestParamInfo<sp::LaplacianForm>& info) {
                           return info.param == sp::LaplacianForm::paper ? "paper" : "consistent";
                         });

}  // namespace
}  // namespace rockcut::fluid::test
