// The ledger's bookings of what a step loses (core/contact_law.hpp, core/rolling_resistance.hpp,
// core/viscous_damping.hpp, core/bond_law.hpp) against velocity Verlet's own energy change: over a
// run that starts and ends with no force acting, the kinetic energy changes by exactly the
// trapezoid work of every force over every drift (the correction between the trapezoid and the
// kicks telescopes to (F_end^2 - F_start^2) dt^2 / 8m, here zero), so a ledger that books each
// loss as the kick and the spring leave it closes to round-off. Each case runs at a coarse step,
// a tenth to a fiftieth of a spring's period, where a booking off by the half step shows.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/dem_system.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

constexpr double kR = 3e-4, kRho = 2800, kKn = 1e10, kKs = 4e9;

double disc_mass() { return kRho * std::numbers::pi * kR * kR; }

// given - held over what came in: the run's kinetic energy at the start is all that came in.
double imbalance(const DemSystem& s, double e0) {
  const EnergyLedger& l = s.ledger();
  const double held = s.kinetic_energy() + s.strain_energy() + l.damping_j + l.friction_j +
                      l.broken_bond_j + l.viscous_damping_j + l.rolling_j;
  return (e0 + l.boundary_work_j + l.external_work_j + l.gravity_work_j - held) / e0;
}

// A bonded pair flying apart until its bond breaks in tension (three steps in), then apart for
// good. Booking the bond's energy at the break (F_now^2 / 2k) instead of what the kick left
// (F_before F_now / 2k) put the ledger 14 % (zeta 0) and 17 % (zeta 0.1) off at this step.
// A softening bond (lambda 3, core/bond_softening.hpp) is booked as the trapezoid less its
// secant energy's change at every step on its way down, and closes the same.
TEST(LedgerBooking, ABondBreakingInTensionClosesTheLedger) {
  for (const auto& [zeta, lambda] : {std::pair{0.0, 0.0}, {0.1, 0.0}, {0.0, 3.0}, {0.1, 3.0}}) {
    Particles p;
    p.add(0.0, 0.0, kR, kRho);
    p.add(2 * kR, 0.0, kR, kRho);
    const double v0 = lambda > 0 ? 1.0 : 0.5;  // a softening bond takes four times the energy
    p.velocity = {-v0, 0.0, v0, 0.0};
    BondSet bonds = test::bond_all_touching(p, {kKn, kKs, 1e3, 1e9, 0.0, lambda});
    DemSettings s;
    s.contact = {0.0, 0.0, 0.0, zeta, 0.0};  // no contacts: the freed pair flies on
    DemSystem sys(std::move(p), s, std::move(bonds));
    const double e0 = disc_mass() * v0 * v0;
    const double period = 2 * std::numbers::pi * std::sqrt(0.5 * disc_mass() / kKn);
    const double dt = period / 20;
    // The dashpots' force at the start (the pair separating at 2 v0) is the one force acting
    // then: the telescoping term, sum |F_0|^2 dt^2 / 8m, is what the kicks gave beyond the
    // trapezoids, and the ledger must be off by exactly that.
    double telescoped = 0.0;
    for (std::size_t i = 0; i < 2; ++i) {
      const double fx = sys.particles().force[2 * i], fy = sys.particles().force[2 * i + 1];
      telescoped += (fx * fx + fy * fy) * dt * dt / (8 * disc_mass());
    }
    for (int k = 0; k < 400; ++k) sys.step(dt);
    ASSERT_EQ(sys.breaks().size(), 1u) << "zeta " << zeta << " lambda " << lambda;
    ASSERT_GT(sys.ledger().broken_bond_j, 1e-3 * e0) << "zeta " << zeta << " lambda " << lambda;
    if (lambda > 0) {
      ASSERT_GT(sys.ledger().bond_softening_j, 0.5 * sys.ledger().broken_bond_j) << zeta;
    }
    EXPECT_NEAR(imbalance(sys, e0), telescoped / e0, 1e-12) << "zeta " << zeta << " lambda " << lambda;
    if (zeta == 0.0) {
      EXPECT_EQ(telescoped, 0.0);
    }
  }
}

// Two discs meeting obliquely with friction, sliding through the contact while its normal force
// rises and falls, then parting: friction, its rolling spring and the dashpots book what the kicks
// took (friction takes about 31 % of the kinetic energy). Booking the limit times the slip left
// 0.40-0.57 % on no line at this step; now the ledger closes to 0.009-0.013 %. The normal
// spring's own error at the steps where the pair meets and parts (its force switching on and off
// within a drift) is Verlet's and is not booked: 0.007 % with friction 0, and the tolerance is
// three times it.
TEST(LedgerBooking, ASlidingCollisionClosesTheLedgerToTheNormalSpringsOwnError) {
  auto collide = [](double mu, double zeta, double mu_r) {
    Particles p;
    p.add(-0.8 * kR - 1e-6, 0.0, kR, kRho);  // 2 um apart along the line of centres
    p.add(0.8 * kR + 1e-6, 1.2 * kR, kR, kRho);
    const double v0 = 0.5;
    p.velocity = {v0, 0.0, -v0, 0.0};
    p.angular_velocity = {5e3, 4e3};
    DemSettings s;
    s.contact = {kKn, kKs, mu, zeta, mu_r};
    DemSystem sys(std::move(p), s);
    const double period = 2 * std::numbers::pi * std::sqrt(0.5 * disc_mass() / kKn);
    const double e0 = sys.kinetic_energy();
    for (int k = 0; k < 600; ++k) sys.step(period / 40);
    EXPECT_EQ(sys.strain_energy(), 0.0) << "the pair must have parted";
    return std::pair{imbalance(sys, e0), sys.ledger().friction_j / e0};
  };
  const auto [frictionless, none] = collide(0.0, 0.0, 0.0);
  EXPECT_EQ(none, 0.0);
  for (const auto& [zeta, mu_r] : {std::pair{0.0, 0.0}, {0.1, 0.0}, {0.0, 0.1}, {0.1, 0.1}}) {
    const auto [imb, friction] = collide(0.5, zeta, mu_r);
    ASSERT_GT(friction, 0.01) << "the pair must slide";
    EXPECT_LT(std::abs(imb), 3 * std::abs(frictionless))
        << "zeta " << zeta << " mu_r " << mu_r << ": friction took " << friction;
  }
}

}  // namespace
}  // namespace rockcut::dem
