// Runtime guards (DESIGN section 5): each one trips on the state it is meant for and stays quiet
// on a healthy one.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/dem_system.hpp"
#include "core/guards.hpp"
#include "core/stability.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

GuardLimits limits_for(const Particles& p, double kn, double ks) {
  return make_guard_limits(p, critical_step(p, kn, ks).dt_s, 0.25, 1.5);
}

TEST(Guards, NanVelocityIsNamedWithItsParticle) {
  Particles p = test::hex_block(4, 4, 1e-3);
  p.velocity[2 * 5 + 1] = std::numeric_limits<double>::quiet_NaN();
  DemSettings s;
  s.contact = {1e10, 2.5e10, 1.0};
  DemSystem system(std::move(p), s);
  const GuardFinding f = check_guards(system, limits_for(system.particles(), 1e10, 2.5e10), 0.0,
                                      system.kinetic_energy());
  ASSERT_TRUE(f.tripped());
  EXPECT_EQ(f.guard, "nan");
  EXPECT_EQ(f.particle, 5);
  EXPECT_DOUBLE_EQ(f.x_m, system.particles().position[10]);
  EXPECT_NE(f.message.find("particle 5"), std::string::npos) << f.message;
}

TEST(Guards, OverlapRatioIsExactAndTripsAboveTheLimit) {
  // Two discs of radius 1 mm and 2 mm whose surfaces overlap by 0.3 mm: 0.3 of the smaller radius.
  for (const double overlap : {0.2e-3, 0.3e-3}) {
    Particles p;
    p.add(0.0, 0.0, 1e-3, 2800);
    p.add(3e-3 - overlap, 0.0, 2e-3, 2800);
    DemSettings s;
    s.contact = {1e10, 2.5e10, 1.0};
    DemSystem system(std::move(p), s);
    EXPECT_NEAR(largest_overlap(system).ratio, overlap / 1e-3, 1e-12);
    EXPECT_EQ(largest_overlap(system).particle, 0);
    GuardLimits g = limits_for(system.particles(), 1e10, 2.5e10);
    g.kinetic_energy_factor = 0;  // the discs push apart from rest: only the overlap guard here
    const GuardFinding f = check_guards(system, g, 0.0, system.kinetic_energy());
    EXPECT_EQ(f.tripped(), overlap > 0.25e-3) << overlap;
    if (f.tripped()) {
      EXPECT_EQ(f.guard, "overlap");
      EXPECT_NEAR(f.value, 0.3, 1e-12);
    }
  }
}

// An undamped bonded block, shaken: at 0.1 of the critical time the energy is conserved and no
// guard trips in 5000 steps; at 3 times it (above the Verlet limit 2 / omega) the energy grows
// without bound and the kinetic-energy guard stops it long before anything overflows.
TEST(Guards, RunawayKineticEnergyTripsOnlyAboveTheStabilityLimit) {
  for (const double factor : {0.1, 3.0}) {
    Particles p = test::hex_block(10, 10, 1e-3);
    for (std::size_t i = 0; i < p.size(); ++i) p.velocity[2 * i] = 1e-3 * (static_cast<double>((i * 7919) % 13) - 6.0);
    BondSet bonds = test::bond_all_touching(p, test::table1_bond());
    DemSettings s;
    s.contact = {1e10, 2.5e10, 1.0};
    DemSystem system(std::move(p), s, std::move(bonds));
    const GuardLimits g = limits_for(system.particles(), 1e10, 2.5e10);
    const double e0 = system.kinetic_energy() + system.strain_energy();
    const double dt = factor * g.critical_time_s;
    GuardFinding f;
    int steps = 0;
    for (; steps < 5000 && !f.tripped(); ++steps) {
      system.step(dt);
      if (steps % 10 == 9) f = check_guards(system, g, e0, system.kinetic_energy());
    }
    if (factor < 1) {
      EXPECT_FALSE(f.tripped()) << f.message;
    } else {
      ASSERT_TRUE(f.tripped());
      EXPECT_EQ(f.guard, "kinetic_energy") << f.message;
      EXPECT_TRUE(std::isfinite(f.value));
      EXPECT_LT(steps, 1000);
    }
  }
}

// The pore fluid is no energy source: a force that keeps pushing a damped disc puts in work the run
// was never given, and the guard names the external force.
TEST(Guards, FluidWorkBeyondTheEnergyGivenTrips) {
  Particles p;
  p.add(0.0, 0.0, 1e-3, 2800);
  p.add(5e-3, 0.0, 1e-3, 2800);
  DemSettings s;
  s.contact = {1e10, 2.5e10, 1.0};
  s.local_damping = 0.7;
  DemSystem system(std::move(p), s);
  const GuardLimits g = limits_for(system.particles(), 1e10, 2.5e10);
  const std::vector<double> push = {10.0, 0.0, 0.0, 0.0};  // N/m on disc 0
  const double dt = 0.2 * g.critical_time_s;
  GuardFinding f;
  for (int k = 0; k < 200000 && !f.tripped(); ++k) {
    system.begin_step(dt);
    system.finish_step(dt, push);
    if (k % 100 == 99) f = check_guards(system, g, 0.0, system.kinetic_energy());
  }
  ASSERT_TRUE(f.tripped());
  EXPECT_EQ(f.guard, "kinetic_energy");
  EXPECT_NE(f.message.find("external (fluid) force"), std::string::npos) << f.message;
  EXPECT_GT(system.ledger().external_work_j, system.kinetic_energy());  // damping took the rest
}

}  // namespace
}  // namespace rockcut::dem
