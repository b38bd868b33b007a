// CSPM operators (paper eqs. 15-17): exact for linear fields on random packings, inside and at the
// surface; the safe fallback where L_i is ill-conditioned.
//
// Tolerance 1e-10 (relative): an exact identity up to round-off. The sums take differences
// a_j - a_i of values of size |a| over distances ~h, so they lose eps |a| / (|grad a| h) ~ 1e-13
// here, and the 2x2 inverse multiplies that by its condition number, at most 1 / kMinEigenRatio
// = 20.
#include <gtest/gtest.h>

#include <cmath>

#include "fluid/sp_test_support.hpp"
#include "sp/operators.hpp"

namespace rockcut::fluid::test {
namespace {

using sp::Boundary;
using sp::Correction;

constexpr double kExact = 1e-10;

struct Counts {
  int full = 0, full_surface = 0, surface = 0;
};

// grad (c0 + cx x + cy y) must be (cx, cy) wherever L_i is fully corrected.
Counts check_linear_gradient(const Initialised& s) {
  const Particles& p = s.particles;
  const double c0 = 2e5, cx = 3e6, cy = -7e6;  // [Pa], [Pa/m]: a pore-pressure-like field
  std::vector<double> a(p.size()), grad(2 * p.size());
  for (std::size_t i = 0; i < p.size(); ++i) a[i] = c0 + cx * p.x(i) + cy * p.y(i);
  sp::gradient(s.geo(), a, grad);
  const double norm = std::hypot(cx, cy);
  Counts c;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool surface = s.geo().div_r[i] <= 1.5;
    c.surface += surface;
    if (s.geo().correction[i] != Correction::full) continue;
    ++c.full;
    c.full_surface += surface;
    EXPECT_LT(std::hypot(grad[2 * i] - cx, grad[2 * i + 1] - cy) / norm, kExact)
        << "particle " << i << " div r " << s.geo().div_r[i];
  }
  return c;
}

TEST(Cspm, GradientOfLinearFieldIsExactOnRandomPackingInsideAndAtSurface) {
  const Initialised s(random_packing(), 0.0015);
  const Counts c = check_linear_gradient(s);
  // Every particle of a dense packing, surface ones included, has a well-conditioned L_i.
  EXPECT_EQ(c.full, static_cast<int>(s.particles.size()));
  EXPECT_GT(c.surface, 150);  // the 30 mm window has ~200 surface particles
  EXPECT_EQ(c.full_surface, c.surface);
}

TEST(Cspm, GradientOfLinearFieldIsExactOnJitteredLattice) {
  const Initialised s(jittered(30, 20, 0.0006, 0.3, 7), 0.0015);
  const Counts c = check_linear_gradient(s);
  EXPECT_EQ(c.full, static_cast<int>(s.particles.size()));
  EXPECT_GT(c.surface, 50);
}

TEST(Cspm, DivergenceOfLinearVelocityIsExact) {
  const Initialised s(random_packing(), 0.0015);
  const Particles& p = s.particles;
  // v = A x + b with trace(A) = -0.7 + 0.2: any linear field, not only a uniform strain.
  std::vector<double> v(2 * p.size()), div(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    v[2 * i] = 0.3 - 0.7 * p.x(i) + 1.1 * p.y(i);
    v[2 * i + 1] = -0.1 + 0.4 * p.x(i) + 0.2 * p.y(i);
  }
  sp::divergence(s.geo(), v, div);
  for (std::size_t i = 0; i < p.size(); ++i) {
    // |grad v| ~ 1.4 1/s is the scale of the error.
    EXPECT_LT(std::abs(div[i] - (-0.5)) / 1.4, kExact) << "particle " << i;
  }
}

TEST(Cspm, InterpolationOfLinearFieldIsExact) {
  const Initialised s(random_packing(), 0.0015);
  const Particles& p = s.particles;
  std::vector<double> a(p.size()), grad(2 * p.size()), out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) a[i] = 2e5 + 3e6 * p.x(i) - 7e6 * p.y(i);
  sp::gradient(s.geo(), a, grad);
  sp::interpolate(s.geo(), sp::WendlandC2(0.0015).w0(), a, grad, out);
  // Relative to the variation of the field over a support, |grad a| h ~ 1e4 Pa.
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_LT(std::abs(out[i] - a[i]) / (7.6e6 * 0.0015), kExact) << "particle " << i;
  }
}

TEST(Cspm, InterpolationWithoutCorrectionIsOnlyFirstOrderAtTheSurface) {
  // Guards the test above: eq. 15 alone (zero gradient term) is not exact for a linear field at a
  // surface, where sum_j V_j (x_j - x_i) W_ij does not vanish.
  const Initialised s(random_packing(), 0.0015);
  const Particles& p = s.particles;
  std::vector<double> a(p.size()), zero(2 * p.size(), 0.0), out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) a[i] = 3e6 * p.x(i);
  sp::interpolate(s.geo(), sp::WendlandC2(0.0015).w0(), a, zero, out);
  double worst = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) worst = std::max(worst, std::abs(out[i] - a[i]));
  EXPECT_GT(worst / (3e6 * 0.0015), 0.05);
}

TEST(Cspm, ChainFallsBackToItsAxisAndLoneParticleToZero) {
  // Five discs on a line at 45 degrees, and one far away: L_i is rank one on the line and zero for
  // the lone disc. The gradient must be the exact derivative along the line, zero across it, and
  // finite everywhere.
  Particles p;
  for (int k = 0; k < 5; ++k) {
    p.position.insert(p.position.end(), {k * 4e-4, k * 4e-4});
    p.radius.push_back(2e-4);
  }
  p.position.insert(p.position.end(), {0.05, 0.0});
  p.radius.push_back(2e-4);
  const Initialised s(p, 0.0015);
  std::vector<double> a(p.size()), grad(2 * p.size());
  for (std::size_t i = 0; i < p.size(); ++i) a[i] = 1e5 + 2e6 * p.x(i) - 5e5 * p.y(i);
  sp::gradient(s.geo(), a, grad);
  const double along = (2e6 - 5e5) / std::sqrt(2.0);  // derivative along (1, 1) / sqrt 2
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(s.geo().correction[i], Correction::projected);
    const double g_along = (grad[2 * i] + grad[2 * i + 1]) / std::sqrt(2.0);
    const double g_across = (grad[2 * i] - grad[2 * i + 1]) / std::sqrt(2.0);
    EXPECT_NEAR(g_along, along, kExact * along);
    EXPECT_NEAR(g_across, 0.0, kExact * along);
  }
  EXPECT_EQ(s.geo().correction[5], Correction::none);
  EXPECT_EQ(grad[10], 0.0);
  EXPECT_EQ(grad[11], 0.0);
}

}  // namespace
}  // namespace rockcut::fluid::test
