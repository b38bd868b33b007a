// The undrained response dp = -alpha M d(eps_v) (eq. 14 without flow) and the cavitation clamp of
// eq. 22, for both models.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "fluid/sp_test_support.hpp"

namespace rockcut::fluid::test {
namespace {

constexpr std::array<bool, 4> kAllSealed = {true, true, true, true};

std::unique_ptr<sp::PorePressureModel> make(const std::string& kind, const sp::SpParams& p) {
  if (kind == "explicit") return std::make_unique<sp::ExplicitModel>(p);
  return std::make_unique<sp::ImplicitModel>(p);
}

class BothModels : public testing::TestWithParam<std::string> {};

TEST_P(BothModels, UndrainedCompressionGivesMinusAlphaMTimesTheVolumetricStrain) {
  // A sealed random packing compressed uniformly: no flow, so every particle gets
  // dp = -alpha M d(eps_v). The model measures d(eps_v) of a step as the CSPM divergence of the
  // displacement on the new positions, exact for this linear field: with a = eps_dot dt per axis,
  // x_new = (1 + a) x_old and div(dx) = 2 a / (1 + a). The pressure must not vary in space: the
  // Laplacian of a uniform field is 0. Tolerance, relative to the change: explicit 1e-8, the
  // rounding of the step's coefficients to floats (sp/step_operator.hpp; each within 6e-8 of its
  // double, with signs that mostly cancel over a row: measured 6e-10 over the 20 steps; a dropped
  // pair or a wrong L_i moves the divergence by 1e-3 or more); implicit 1e-7, the solver's: each
  // step's increment is solved to a relative residual of 1e-8, i.e. to ~3e-8 with the condition
  // number (~3) of the step's matrix.
  // The paper's force form (-grad p pi r^2, CSPM) so that the uniform pressure exerts none;
  // the adjoint form pushes the surface grains against the walls instead (adjoint_force_test).
  sp::SpParams params = table1(0.0015, kAllSealed);
  params.force_form = sp::ForceForm::gradient;
  auto model = make(GetParam(), params);
  Driver drive(*model, random_packing());
  const double rate = -0.5, dt = 5e-6;  // [1/s] per axis: eps_v = -1e-5 per step
  const double expected = compress_undrained(drive, params, rate, dt, 20);
  const double change = expected - params.p_hydro_pa;  // +1e5 Pa: compression raises p
  EXPECT_NEAR(change, 0.5 * 2e9 * 1e-4, 0.5 * 2e9 * 1e-4 * 1e-4);  // alpha M |eps_v|, to O(a)
  const double tolerance = GetParam() == "explicit" ? 1e-8 : 1e-7;
  for (double p : model->pressure()) EXPECT_NEAR(p, expected, tolerance * change);
  // And the force -grad p pi r^2 is zero up to the same tolerance over a kernel support.
  for (double f : drive.force()) EXPECT_LT(std::abs(f), tolerance * change / 0.0015 * 5e-7);
}

TEST_P(BothModels, CavitationClampHoldsAtPMinAndReleasesOnCompression) {
  // Eq. 22 in a sealed, uniformly dilated block (no flow: every particle alike). Dilation lowers
  // p by alpha M eps_dot dt per step until p_min; there it holds exactly, however long the
  // dilation continues (the vapour takes up the volume: no deficit is remembered). Compression
  // then raises p from p_min at once, by alpha M |eps_dot| dt per step.
  const sp::SpParams params = table1(0.0015, kAllSealed);
  auto model = make(GetParam(), params);
  Driver drive(*model, lattice(12, 12, 0.0006, 0.0003));
  const double dt = 5e-6, rate = 0.5;  // dilation per axis: dp = -alpha M * 2 * 2.5e-6 = -5 kPa/step
  int steps_to_clamp = 0;
  for (int k = 0; k < 60; ++k) {
    drive.step(dt, rate, rate);
    for (double p : model->pressure()) ASSERT_GE(p, params.p_min_pa);
    if (model->cavitated() == 0) ++steps_to_clamp;
  }
  // (101325 - 2340) / 5000 = 19.8: clamped from the 20th step on, and held for the other 40.
  EXPECT_EQ(steps_to_clamp, 19);
  EXPECT_EQ(model->cavitated(), model->pressure().size());
  for (double p : model->pressure()) EXPECT_EQ(p, params.p_min_pa);

  const double am = params.alpha * params.bulk_modulus_pa;
  double expected = params.p_min_pa;
  for (int k = 0; k < 3; ++k) {
    drive.step(dt, -rate, -rate);
    const double a = -rate * dt;
    expected += -am * 2.0 * a / (1.0 + a);
    EXPECT_EQ(model->cavitated(), 0u);
    for (double p : model->pressure()) EXPECT_NEAR(p, expected, 1e-9 * params.p_hydro_pa);
  }
}

TEST_P(BothModels, CavitatedZoneRefillsByFlowFromTheDrainedSurface) {
  // Eq. 22's other release: a block drained at the top, sealed elsewhere, is dilated until its
  // inside cavitates, then held still. Water flows in from the top; a clamped particle leaves
  // p_min only when its inflow makes dp/dt > 0, so while held the pressure never decreases
  // anywhere below p_hydro... and every particle is eventually released.
  sp::SpParams params = table1(0.0015, {true, true, true, false});
  params.permeability_m2 = 1e-16;  // D = 2e-4 m^2/s: the 12 mm block drains in ~0.7 s
  auto model = make(GetParam(), params);
  Driver drive(*model, lattice(20, 20, 0.0006, 0.0003));
  const double dt = 5e-5;  // explicit limit 0.05 h^2 / D = 5.6e-4 s
  for (int k = 0; k < 20; ++k) drive.step(dt, 0.0, 1.0);  // -alpha M 1e-3: deep below p_min
  const std::size_t cavitated = model->cavitated();
  EXPECT_GT(cavitated, model->pressure().size() / 2);
  std::vector<double> previous(model->pressure().begin(), model->pressure().end());
  std::size_t released_first = 0;
  for (int k = 0; k < 4000 && model->cavitated() > 0; ++k) {
    drive.step(10 * dt, 0.0, 0.0);
    for (std::size_t i = 0; i < previous.size(); ++i) {
      // Only increases pass while held still (inflow from the drained top).
      ASSERT_GE(model->pressure()[i], previous[i] - 1e-9 * params.p_hydro_pa) << "particle " << i;
    }
    if (released_first == 0 && model->cavitated() < cavitated) released_first = model->cavitated();
    previous.assign(model->pressure().begin(), model->pressure().end());
  }
  EXPECT_EQ(model->cavitated(), 0u);
  EXPECT_GT(released_first, 0u);  // released progressively, not all at once
}

INSTANTIATE_TEST_SUITE_P(Sp, BothModels, testing::Values("explicit", "implicit"));

}  // namespace
}  // namespace rockcut::fluid::test
