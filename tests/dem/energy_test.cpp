// Energy: conserved without damping (velocity Verlet), dissipated with it.
#include <gtest/gtest.h>

#include <random>

#include "core/dem_system.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

DemSystem shaken_block(double damping) {
  Particles p = test::hex_block(10, 10, 1e-3);
  std::mt19937_64 rng(7);
  for (double& v : p.velocity) v = 1e-3 * ((rng() >> 11) * 0x1.0p-53 - 0.5);
  BondSet bonds = test::bond_all_touching(p, test::table1_bond());
  DemSettings s;
  s.contact = {1e10, 2.5e10, 1.0};
  s.local_damping = damping;
  return DemSystem(std::move(p), s, std::move(bonds));
}

// Critical step sqrt(m / k) for the smallest disc; the run uses a tenth of it.
double stable_dt() {
  const double m = 2800 * M_PI * 1e-6;
  return 0.1 * std::sqrt(m / 2.5e10);
}

TEST(Energy, DriftWithoutDampingStaysBelow1e4Over1e5Steps) {
  // Velocity Verlet conserves a shadow energy: the sampled energy fluctuates by O((omega dt)^2)
  // (about 1 % at this step, where omega dt ~ 0.5 for the stiffest rotational mode) but does not
  // drift. Drift is the change of the mean over a window of 1e4 steps from the first to the last.
  DemSystem s = shaken_block(0.0);
  const double dt = stable_dt();
  const int steps = 100000, window = 10000;
  double first = 0.0, last = 0.0;
  for (int k = 0; k < steps; ++k) {
    s.step(dt);
    const double e = s.kinetic_energy() + s.strain_energy();
    if (k < window) first += e / window;
    if (k >= steps - window) last += e / window;
  }
  EXPECT_EQ(s.breaks().size(), 0u);
  EXPECT_LT(std::abs(last - first) / first, 1e-4);
}

TEST(Energy, DampingDissipatesMonotonically) {
  DemSystem s = shaken_block(0.7);
  const double dt = stable_dt();
  double last_dissipated = 0.0;
  double last_energy = s.kinetic_energy() + s.strain_energy();
  const double e0 = last_energy;
  for (int k = 0; k < 20000; ++k) {
    s.step(dt);
    EXPECT_GE(s.ledger().damping_j, last_dissipated);
    last_dissipated = s.ledger().damping_j;
    // Sampled every 500 steps, until round-off: below 1e-9 e0 the bond forces are
    // ~1e-4.5 of their start and their energy F^2/2k is no longer resolved.
    if (k % 500 == 499 && last_energy > 1e-9 * e0) {
      const double e = s.kinetic_energy() + s.strain_energy();
      EXPECT_LT(e, last_energy);
      last_energy = e;
    }
  }
  EXPECT_LT(last_energy, 0.05 * e0);
  // The mechanical energy lost is what damping dissipated (no other sink here): 1 % for the
  // O(dt) quadrature of the damping work.
  EXPECT_NEAR((e0 - last_energy) / s.ledger().damping_j, 1.0, 0.01);
}

}  // namespace
}  // namespace rockcut::dem
