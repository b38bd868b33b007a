// Bonds (paper section 3.1, figure 4): they break at T_n in tension and at T_s in shear, within one
// step's load increment, never in compression, and the broken pair may still collide.
#include <gtest/gtest.h>

#include <cmath>

#include "core/dem_system.hpp"
#include "core/specimen_generator.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

TEST(Bond, BreaksInTensionAtTn) {
  const BondLaw law = test::table1_bond();
  const double v = 1e-3, dt = 1e-8;
  const double increment = law.normal_stiffness_pa * v * dt;  // load added per step [N/m]
  DemSystem s = test::driven_pair(v, 0.0, law);
  ASSERT_EQ(s.bonds().size(), 1u);
  double last_force = 0.0;
  while (s.bonds().size() == 1 && s.step_count() < 10'000'000) {
    last_force = -s.bonds().normal_force(0, s.particles());
    s.step(dt);
  }
  ASSERT_EQ(s.breaks().size(), 1u);
  EXPECT_EQ(s.breaks()[0].mode, BreakMode::tensile);
  // The last force carried is below T_n and within one increment of it.
  EXPECT_LE(last_force, law.tensile_strength_n_per_m);
  EXPECT_GT(last_force, law.tensile_strength_n_per_m - increment * (1 + 1e-9));
}

TEST(Bond, BreaksInShearAtTs) {
  const BondLaw law = test::table1_bond();
  const double v = 1e-3, dt = 1e-8;
  const double increment = law.shear_stiffness_pa * v * dt;
  DemSystem s = test::driven_pair(0.0, v, law);
  double last_shear = 0.0;
  while (s.bonds().size() == 1 && s.step_count() < 10'000'000) {
    last_shear = std::abs(s.bonds().shear_force(0));
    s.step(dt);
  }
  ASSERT_EQ(s.breaks().size(), 1u);
  EXPECT_EQ(s.breaks()[0].mode, BreakMode::shear);
  EXPECT_LE(last_shear, law.shear_strength_n_per_m);
  // The normal part of the motion is second order (the pair rotates), so the shear increment
  // per step is k_s v dt to within 1e-6.
  EXPECT_GT(last_shear, law.shear_strength_n_per_m - increment * 1.000001);
}

// A Mohr-Coulomb bond (dem.bonds.friction_angle_deg): sheared while compressed, it breaks in
// shear when |F_t| reaches T_s + tan(phi_b) F_n, not at T_s; phi_b 0 is the paper's bond.
TEST(Bond, FrictionAngleRaisesTheShearStrengthByTanPhiTimesTheCompression) {
  for (const double phi_deg : {0.0, 30.0}) {
    BondLaw law = test::table1_bond();
    law.friction_coefficient = std::tan(phi_deg * std::acos(-1.0) / 180.0);
    const double v = 1e-3, dt = 1e-8;
    DemSystem s = test::driven_pair(-v, v, law);  // closing and sliding at once
    double last_shear = 0.0, last_normal = 0.0;
    while (s.bonds().size() == 1 && s.step_count() < 10'000'000) {
      last_shear = std::abs(s.bonds().shear_force(0));
      last_normal = s.bonds().normal_force(0, s.particles());
      s.step(dt);
    }
    ASSERT_EQ(s.breaks().size(), 1u) << phi_deg;
    EXPECT_EQ(s.breaks()[0].mode, BreakMode::shear) << phi_deg;
    const double strength = law.shear_strength_n_per_m + law.friction_coefficient * last_normal;
    // Below the strength at the last step carried, within one step's increments of it (shear
    // k_s v dt less what tan(phi_b) k_n v dt adds).
    const double increment =
        (law.shear_stiffness_pa + law.friction_coefficient * law.normal_stiffness_pa) * v * dt;
    EXPECT_LE(last_shear, strength) << phi_deg;
    EXPECT_GT(last_shear, strength - 1.01 * increment) << phi_deg;
    if (phi_deg > 0) {
      EXPECT_GT(last_shear, 1.2 * law.shear_strength_n_per_m);  // 1.30 T_s here
    }
  }
}

TEST(Bond, NeverBreaksInCompressionAndCarriesIt) {
  const BondLaw law = test::table1_bond();
  DemSystem s = test::driven_pair(-0.1, 0.0, law);
  for (int k = 0; k < 20000; ++k) s.step(1e-8);  // 20 um closer: 20 times T_n / k_n
  EXPECT_EQ(s.bonds().size(), 1u);
  EXPECT_GT(s.bonds().normal_force(0, s.particles()), 5 * law.tensile_strength_n_per_m);
}

TEST(Bond, BrokenPairStillCollides) {
  const BondLaw law = test::table1_bond();
  DemSystem s = test::driven_pair(1e-3, 0.0, law);
  while (s.bonds().size() == 1) s.step(1e-8);
  EXPECT_EQ(s.contacts().size(), 1u) << "the freed pair joins the contact list";
}

// A bond pressed together and sheared breaks in shear; the contact spring that replaces it keeps
// the overlap's normal energy. The strain energy plus the broken bonds' energy must therefore run on
// through the break, changing by one step's work only (k dx per step: about 3e-7 J/m here), where
// booking the whole bond energy as released would jump by the normal part, 1/2 F_n^2 / k_n
// (about 3e-3 J/m at the break).
TEST(Bond, ShearBreakUnderCompressionBooksOnlyTheReleasedEnergy) {
  const BondLaw law = test::table1_bond();
  const double dt = 1e-8;
  DemSystem s = test::driven_pair(-1e-3, 1e-3, law);
  double before = 0.0, normal_force = 0.0;
  while (s.bonds().size() == 1 && s.step_count() < 10'000'000) {
    before = s.strain_energy() + s.ledger().broken_bond_j;
    normal_force = s.bonds().normal_force(0, s.particles());
    s.step(dt);
  }
  ASSERT_EQ(s.breaks().size(), 1u);
  ASSERT_EQ(s.breaks()[0].mode, BreakMode::shear);
  const double kept = 0.5 * normal_force * normal_force / law.normal_stiffness_pa;
  ASSERT_GT(kept, 1e-3) << "the pair must be pressed hard enough for the test to tell";
  const double after = s.strain_energy() + s.ledger().broken_bond_j;
  EXPECT_NEAR(after, before, 1e-6) << "energy kept by the contact: " << kept << " J/m";
}

TEST(Bond, InstallationBondsTouchingPairsOnly) {
  Particles p = test::hex_block(6, 5, 1e-3);
  BondSet b = test::bond_all_touching(p, test::table1_bond());
  // A 6 x 5 hexagonal block: 5 bonds per row along x (25), and between consecutive rows each disc
  // touches two above except at the row ends: 4 row gaps * (2 * 6 - 1) = 44.
  EXPECT_EQ(b.size(), 25u + 44u);
}

}  // namespace
}  // namespace rockcut::dem

namespace rockcut::dem {
namespace {

TEST(Bond, BondedBlockAtRestStaysExactlyAtRest) {
  // A generated packing bonded where it touches: every bond sits at its rest length, so every
  // force is exactly zero and nothing may move, not even by round-off. The bond force must use
  // the same length arithmetic as the rest length it was installed with; the older
  // rest - d^2 / sqrt(d^2) differed in the last bit and set a relaxed block in motion (kinetic
  // energy ~1e-23 J/m after 570 steps of the reduced scene) with no work on any ledger.
  PackingSpec spec;
  spec.region.width_m = 0.02;
  spec.region.height_m = 0.01;
  spec.radius_min_m = 2e-4;
  spec.radius_max_m = 4e-4;
  spec.seed = 7;
  const Packing packing = generate_packing(spec);
  Particles p;
  for (std::size_t i = 0; i < packing.size(); ++i) {
    p.add(packing.x_m[i], packing.y_m[i], packing.radius_m[i], 2650);
  }
  CellGrid grid;
  BondSet bonds = BondSet::install(p, test::table1_bond(), 1e-9, grid);
  ASSERT_GT(bonds.size(), packing.size()) << "the test needs a bonded block";
  for (int threads : {1, 2}) {
    DemSettings s;
    s.contact = {1e10, 2.5e10, 0.5};
    s.local_damping = 0.7;
    s.threads = threads;
    DemSystem block(p, s, bonds);
    for (int k = 0; k < 2000; ++k) block.step(5e-8);
    for (double f : block.particles().force) ASSERT_EQ(f, 0.0) << threads << " threads";
    for (double v : block.particles().velocity) ASSERT_EQ(v, 0.0) << threads << " threads";
    EXPECT_EQ(block.kinetic_energy(), 0.0);
    EXPECT_EQ(block.strain_energy(), 0.0);
    EXPECT_EQ(block.ledger().damping_j, 0.0);
  }
}

}  // namespace
}  // namespace rockcut::dem
