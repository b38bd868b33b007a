// Softening bonds (core/bond_softening.hpp): past its strength a bond gives way along a linear
// envelope over lambda times its elastic span, unloads along its secant, and takes
// (1 + lambda) T^2 / (2 k) to break, in tension and in shear; lambda = 0 is the paper's brittle
// bond, bit for bit.
#include <gtest/gtest.h>

#include <cmath>

#include "core/bond_softening.hpp"
#include "core/dem_system.hpp"
#include "dem/dem_test_support.hpp"
#include "wire/state_archive.hpp"

namespace rockcut::dem {
namespace {

constexpr double kLambda = 3.0;

BondLaw softening_law(double lambda = kLambda) {
  BondLaw law = test::table1_bond();
  law.softening_ratio = lambda;
  return law;
}

double opening(const DemSystem& s) {
  const auto& x = s.particles().position;
  return std::hypot(x[2] - x[0], x[3] - x[1]) - 6e-4;
}

// Pulled apart at a constant rate, the bond's force follows the envelope: k_n delta up to T_n at
// delta_p, then T_n (1 - D) down to zero at delta_u = (1 + lambda) delta_p, where it breaks in
// tension; the ledger then holds the area under the envelope, G_b = (1 + lambda) T_n^2 / 2k_n,
// nearly all of it dissipated by softening (what the break itself releases is the last step's).
// The tolerances are one step's load increment (k_n v dt = 1 N/m, 1e-4 T_n) and its energy.
TEST(SofteningBond, FollowsTheTensileEnvelopeAndTakesItsAreaToBreak) {
  const BondLaw law = softening_law();
  const double v = 1e-2, dt = 1e-8;
  const double increment = law.normal_stiffness_pa * v * dt;
  const double tn = law.tensile_strength_n_per_m, delta_p = tn / law.normal_stiffness_pa;
  DemSystem s = test::driven_pair(v, 0.0, law);
  double peak = 0.0, at_half_span = -1.0, last_opening = 0.0;
  while (s.bonds().size() == 1 && s.step_count() < 10'000'000) {
    const double t = -s.bonds().normal_force(0, s.particles());
    peak = std::max(peak, t);
    last_opening = opening(s);
    if (at_half_span < 0 && last_opening >= (1 + 0.5 * kLambda) * delta_p) at_half_span = t;
    s.step(dt);
  }
  ASSERT_EQ(s.breaks().size(), 1u);
  EXPECT_EQ(s.breaks()[0].mode, BreakMode::tensile);
  EXPECT_LE(peak, tn);
  EXPECT_GT(peak, tn - increment * (1 + 1e-9));
  EXPECT_NEAR(at_half_span, 0.5 * tn, 2 * increment);  // D = 1/2 halfway down the branch
  EXPECT_NEAR(last_opening, (1 + kLambda) * delta_p, 2 * v * dt);
  const double g_b = tensile_fracture_work(law.normal_stiffness_pa, tn, kLambda);
  EXPECT_NEAR(g_b, 0.5 * 4 * 1e4 * 1e4 / 1e10, 1e-15);  // 0.02 J/m: four brittle bonds' worth
  EXPECT_NEAR(s.ledger().broken_bond_j, g_b, 1e-4 * g_b);
  EXPECT_GT(s.ledger().bond_softening_j, 0.999 * g_b);
  EXPECT_LE(s.ledger().bond_softening_j, s.ledger().broken_bond_j);
}

// Pulled to D = 1/2 and pushed back: the force falls along the secant k_n (1 - D)/(1 + lambda D)
// (a fifth of k_n here) with no further loss, the crack closes and compression takes k_n again;
// pulled once more, the bond reloads along the secant to the envelope and goes on softening from
// where it stopped.
TEST(SofteningBond, UnloadsAlongItsSecantAndClosesUnderCompression) {
  const BondLaw law = softening_law();
  const double v = 1e-2, dt = 1e-8;
  const double increment = law.normal_stiffness_pa * v * dt;
  const double tn = law.tensile_strength_n_per_m, delta_p = tn / law.normal_stiffness_pa;
  DemSystem s = test::driven_pair(v, 0.0, law);
  while (opening(s) < 2.5 * delta_p) s.step(dt);
  const double damage = s.bonds().damage(0);
  EXPECT_NEAR(damage, 0.5, 2 * v * dt / (kLambda * delta_p));
  const double softened = s.ledger().bond_softening_j;
  s.particles_for_driving().velocity[2] = -v;
  while (opening(s) > 1.25 * delta_p) s.step(dt);
  const double secant = law.normal_stiffness_pa * (1 - damage) / (1 + kLambda * damage);
  EXPECT_NEAR(secant, 0.2 * law.normal_stiffness_pa, 1e-4 * law.normal_stiffness_pa);
  EXPECT_NEAR(-s.bonds().normal_force(0, s.particles()), secant * opening(s), 1e-6 * tn);
  EXPECT_EQ(s.bonds().damage(0), damage);
  EXPECT_NEAR(s.ledger().bond_softening_j, softened, 1e-9 * softened) << "unloading is elastic";
  while (opening(s) > -delta_p) s.step(dt);
  EXPECT_NEAR(s.bonds().normal_force(0, s.particles()), -law.normal_stiffness_pa * opening(s),
              1e-6 * tn);
  EXPECT_NEAR(s.ledger().bond_softening_j, softened, 1e-6 * softened)
      << "only the step across the closing crack's kink books a little";
  s.particles_for_driving().velocity[2] = v;
  double peak_on_reload = 0.0;
  while (s.bonds().damage(0) == damage && s.step_count() < 10'000'000) {
    peak_on_reload = std::max(peak_on_reload, -s.bonds().normal_force(0, s.particles()));
    s.step(dt);
  }
  EXPECT_NEAR(peak_on_reload, 0.5 * tn, 2 * increment) << "back on the envelope at D = 1/2";
  while (s.bonds().size() == 1 && s.step_count() < 10'000'000) s.step(dt);
  const double g_b = tensile_fracture_work(law.normal_stiffness_pa, tn, kLambda);
  EXPECT_NEAR(s.ledger().broken_bond_j, g_b, 1e-4 * g_b) << "the cycle changed nothing";
}

// Sheared at a constant rate: the shear force rises to T_s, then falls linearly to zero over
// lambda times the elastic slip; the work to break is (1 + lambda) T_s^2 / 2k_s. The pair
// rotates a little as it shears (second order), hence the looser tolerance.
TEST(SofteningBond, SoftensInShearOverLambdaTimesItsElasticSlip) {
  const BondLaw law = softening_law();
  const double v = 1e-2, dt = 1e-8;
  const double ts = law.shear_strength_n_per_m, ks = law.shear_stiffness_pa;
  DemSystem s = test::driven_pair(0.0, v, law);
  double peak = 0.0;
  std::uint64_t steps_at_peak = 0;
  while (s.bonds().size() == 1 && s.step_count() < 10'000'000) {
    const double f = std::abs(s.bonds().shear_force(0));
    if (f > peak) {
      peak = f;
      steps_at_peak = s.step_count();
    }
    s.step(dt);
  }
  ASSERT_EQ(s.breaks().size(), 1u);
  EXPECT_EQ(s.breaks()[0].mode, BreakMode::shear);
  EXPECT_NEAR(peak, ts, 1e-3 * ts);
  const double slip_p = ts / ks;
  const double slip_softening = static_cast<double>(s.step_count() - steps_at_peak) * v * dt;
  EXPECT_NEAR(slip_softening, kLambda * slip_p, 1e-2 * slip_p);
  const double g_s = 0.5 * (1 + kLambda) * ts * ts / ks;
  EXPECT_NEAR(s.ledger().broken_bond_j, g_s, 1e-2 * g_s);
}

// The damage is state: a pair saved halfway down its envelope and loaded into a fresh system goes
// on to the same break at the same step with the same ledger, bit for bit.
TEST(SofteningBond, ItsDamageIsSavedAndLoadedWithTheState) {
  const BondLaw law = softening_law();
  const double v = 1e-2, dt = 1e-8, delta_p = law.tensile_strength_n_per_m / law.normal_stiffness_pa;
  DemSystem reference = test::driven_pair(v, 0.0, law);
  while (opening(reference) < 2.5 * delta_p) reference.step(dt);
  ASSERT_GT(reference.bonds().damage(0), 0.4);
  state::StateArchive archive;
  reference.save_state(archive);
  DemSystem resumed = test::driven_pair(v, 0.0, law);
  resumed.load_state(archive);
  EXPECT_EQ(resumed.bonds().damage(0), reference.bonds().damage(0));
  EXPECT_EQ(resumed.ledger().bond_softening_j, reference.ledger().bond_softening_j);
  while (reference.bonds().size() == 1 && reference.step_count() < 10'000'000) {
    reference.step(dt);
    resumed.step(dt);
    ASSERT_EQ(resumed.bonds().size(), reference.bonds().size());
  }
  EXPECT_EQ(resumed.step_count(), reference.step_count());
  EXPECT_EQ(resumed.ledger().broken_bond_j, reference.ledger().broken_bond_j);
  EXPECT_EQ(resumed.ledger().bond_softening_j, reference.ledger().bond_softening_j);
}

// lambda = 0 is the paper's bond: the same breaks at the same steps, bit for bit, as a bond law
// without the field.
TEST(SofteningBond, LambdaZeroIsThePapersBrittleBond) {
  for (const auto& [vx, vy] : {std::pair{1e-2, 0.0}, {0.0, 1e-2}}) {
    DemSystem brittle = test::driven_pair(vx, vy, test::table1_bond());
    DemSystem zero = test::driven_pair(vx, vy, softening_law(0.0));
    while (brittle.bonds().size() == 1 && brittle.step_count() < 10'000'000) {
      brittle.step(1e-8);
      zero.step(1e-8);
      ASSERT_EQ(zero.bonds().size(), brittle.bonds().size());
      if (zero.bonds().size() == 1) {
        ASSERT_EQ(zero.bonds().damage(0), 0.0);
      }
    }
    EXPECT_EQ(zero.step_count(), brittle.step_count());
    EXPECT_EQ(zero.ledger().broken_bond_j, brittle.ledger().broken_bond_j);
    EXPECT_EQ(zero.ledger().bond_softening_j, 0.0);
  }
}

}  // namespace
}  // namespace rockcut::dem
