// Each grain's own undrained stiffness K_ii (sp/self_stiffness.cpp), the block the DEM applies
// between exchanges under Coupling.fluid_stiffness "self", against a finite difference of the
// model's own force.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <omp.h>

#include "fluid/sp_test_support.hpp"

namespace rockcut::fluid::test {
namespace {

// Sealed on three sides, drained at the top: interior grains, sealed-wall grains and drained
// surface grains (whose own pressure is held and so adds nothing) are all in the packing.
constexpr std::array<bool, 4> kSelfStiffnessSides = {true, true, true, false};
constexpr double kSelfStiffnessH = 0.0015;


// The force after displacing grain i alone by u (one fluid step of dt), minus the force before.
std::array<double, 2> force_change(const Particles& p, std::size_t i, double ux, double uy,
                                   const std::vector<double>& force0) {
  sp::ExplicitModel model(table1(kSelfStiffnessH, kSelfStiffnessSides));
  std::vector<double> x = p.position, v(x.size(), 0.0), d(x.size(), 0.0), f(x.size(), 0.0);
  model.initialise({p.radius, p.position});
  model.step(0.0, 0.0, {x, v, d, {}}, f);
  // A fluid step short enough that nothing flows (D dt / h^2 ~ 1e-8): the undrained answer.
  const double dt = 1e-9;
  d[2 * i] = ux;
  d[2 * i + 1] = uy;
  x[2 * i] += ux;
  x[2 * i + 1] += uy;
  v[2 * i] = ux / dt;
  v[2 * i + 1] = uy / dt;
  model.step(dt, dt, {x, v, d, {}}, f);
  return {f[2 * i] - force0[2 * i], f[2 * i + 1] - force0[2 * i + 1]};
}

TEST(FluidSelfStiffness, IsTheGrainsOwnBlockOfTheUndrainedForce) {
  // dF_i = -K_ii u_i for a displacement u of grain i alone. u = 1e-9 m is 1e-6 of a radius: the
  // geometry is reused (no refresh below 0.01 h), so the step is exactly linear in u, and the
  // pressure moves by ~alpha M |div u| ~ 1 kPa, far from cavitation. Tolerance 1e-5 of the
  // block's largest entry: measured within 8e-7 of it (the rounding of the force difference, a
  // change of ~0.1-2 N/m against forces of ~1e2 N/m, and of the float coefficients); a missing
  // neighbour term or a wrong weight moves an entry by 1e-2 of it or more.
  const Particles p = random_packing();
  sp::ExplicitModel model(table1(kSelfStiffnessH, kSelfStiffnessSides));
  std::vector<double> x = p.position, v(x.size(), 0.0), d(x.size(), 0.0), f0(x.size(), 0.0);
  model.initialise({p.radius, p.position});
  model.step(0.0, 0.0, {x, v, d, {}}, f0);
  std::vector<double> k;
  ASSERT_TRUE(model.self_stiffness(k));
  ASSERT_EQ(k.size(), 3 * p.size());

  // The grain nearest the centre, one on the sealed bottom, one at the drained top.
  std::size_t centre = 0, bottom = 0, top = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = std::hypot(p.x(i), p.y(i)), rc = std::hypot(p.x(centre), p.y(centre));
    if (r < rc) centre = i;
    if (std::abs(p.x(i)) < 0.005 && p.y(i) < p.y(bottom)) bottom = i;
    if (std::abs(p.x(i)) < 0.005 && p.y(i) > p.y(top)) top = i;
  }
  const double u = 1e-9;
  int positive = 0;
  for (std::size_t i : {centre, bottom, top}) {
    const double kxx = k[3 * i], kxy = k[3 * i + 1], kyy = k[3 * i + 2];
    const double scale = std::max({std::abs(kxx), std::abs(kxy), std::abs(kyy)});
    const auto dx = force_change(p, i, u, 0.0, f0);
    const auto dy = force_change(p, i, 0.0, u, f0);
    EXPECT_NEAR(-dx[0] / u, kxx, 1e-5 * scale) << "grain " << i;
    EXPECT_NEAR(-dx[1] / u, kxy, 1e-5 * scale) << "grain " << i;
    EXPECT_NEAR(-dy[0] / u, kxy, 1e-5 * scale) << "grain " << i;
    EXPECT_NEAR(-dy[1] / u, kyy, 1e-5 * scale) << "grain " << i;
    // A stiffness: positive definite (alpha M A D^T D restricted to one grain).
    EXPECT_GT(kxx, 0.0);
    EXPECT_GT(kxx * kyy - kxy * kxy, 0.0);
    if (scale > 0.0) ++positive;
  }
  EXPECT_EQ(positive, 3);
  // Its size: alpha M (1e9 Pa) times A |C|^2, with |C| ~ 1 / h and A ~ r^2: of order 1e8 Pa.
  EXPECT_GT(k[3 * centre], 1e7);
  EXPECT_LT(k[3 * centre], 1e11);
}

TEST(FluidSelfStiffness, GivesTheSameBitsWithOneAndTwoThreadsAndFollowsTheGeometry) {
  // One value per grain from its own row: the thread count changes nothing. A second call on the
  // same geometry returns the cached block; a refresh of the geometry recomputes it.
  const Particles p = random_packing();
  std::vector<double> k1, k2, again;
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    sp::ExplicitModel model(table1(kSelfStiffnessH, kSelfStiffnessSides));
    std::vector<double> x = p.position, v(x.size(), 0.0), d(x.size(), 0.0), f(x.size(), 0.0);
    model.initialise({p.radius, p.position});
    model.step(0.0, 0.0, {x, v, d, {}}, f);
    ASSERT_TRUE(model.self_stiffness(threads == 1 ? k1 : k2));
    if (threads == 2) {
      ASSERT_TRUE(model.self_stiffness(again));
      EXPECT_EQ(again, k2);
      // A uniform compression of 1 % moves the grains past the refresh distance: the geometry
      // is rebuilt, and its block must be too.
      for (std::size_t i = 0; i < x.size(); ++i) {
        d[i] = -0.01 * x[i];
        x[i] += d[i];
      }
      model.step(1e-9, 1e-9, {x, v, d, {}}, f);
      ASSERT_TRUE(model.self_stiffness(again));
      EXPECT_NE(again, k2);
    }
  }
  omp_set_num_threads(1);
  EXPECT_EQ(k1, k2);
}

}  // namespace
}  // namespace rockcut::fluid::test
