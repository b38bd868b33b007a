// The fluid's force between exchanges (core/fluid_force_extrapolation.hpp): held, or extrapolated
// on the line through the last two exchanges. Driven here as the coupler drives the DEM: N - 1
// full steps, then a split step completed with the fluid's force at its end.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "core/dem_system.hpp"
#include "core/lattice.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

using test::two_discs;

constexpr double kDt = 1e-4;
constexpr double kForce0 = 3e-3;      // [N/m] on disc 0 in x at t = 0
constexpr double kForceRate = 40.0;   // [N/(m s)]: the force rises linearly in time
constexpr double kSideForce = -1e-3;  // [N/m] on disc 1 in y, constant

std::vector<double> force_at(double t_s) {
  return {kForce0 + kForceRate * t_s, 0.0, 0.0, kSideForce};
}

/// `exchanges` exchanges of N steps each, the fluid's force sampled at each exchange.
DemSystem run(unsigned n, unsigned exchanges, bool extrapolate) {
  DemSystem s(two_discs(), {});
  s.extrapolate_external_force(extrapolate);
  s.set_external_force(force_at(0.0));
  for (unsigned m = 0; m < exchanges; ++m) {
    for (unsigned k = 0; k + 1 < n; ++k) s.step(kDt);
    s.begin_step(kDt);
    s.finish_step(kDt, force_at(s.time_s()));
  }
  return s;
}

TEST(FluidForceExtrapolation, ExtrapolatedForceIsTheFluidsOwnBetweenExchangesOfALinearRamp) {
  // Sampled every step (N = 1) the disc feels F(t) exactly. With N = 5 the first exchange has no
  // line yet (rate 0), so its 4 steps lack part of the ramp; from then on the extrapolated force
  // is the ramp's own, and the velocity deficit stays what the first exchange left. Held, the
  // force lags by up to 4 steps at every exchange and the deficit grows with each.
  const unsigned n = 5;
  const DemSystem exact = run(1, n * 101, false);
  const DemSystem after_one = run(1, n, false);
  const DemSystem extrapolated_one = run(n, 1, true);
  const double first_deficit =
      after_one.particles().velocity[0] - extrapolated_one.particles().velocity[0];
  ASSERT_GT(first_deficit, 0.0);

  const DemSystem extrapolated = run(n, 101, true);
  const DemSystem held = run(n, 101, false);
  ASSERT_EQ(extrapolated.step_count(), exact.step_count());
  const double v_exact = exact.particles().velocity[0];
  // Round-off of 505 steps of a velocity about 2e4 times the deficit: 1e-9 of the deficit.
  EXPECT_NEAR(v_exact - extrapolated.particles().velocity[0], first_deficit,
              1e-9 * std::abs(first_deficit) + 1e3 * 505 * 1e-16 * std::abs(v_exact));
  // Held: 101 exchanges each lagging like the first (the ramp's slope is the same in each).
  EXPECT_NEAR((v_exact - held.particles().velocity[0]) / first_deficit, 101.0, 1e-6);
  // The constant force on disc 1 is not changed by the line through two equal values.
  EXPECT_EQ(extrapolated.particles().velocity[3], exact.particles().velocity[3]);
}

TEST(FluidForceExtrapolation, AtOneStepPerExchangeNothingChangesABit) {
  // N = 1 has no step between exchanges: each exchange replaces the moved-on force.
  const DemSystem held = run(1, 300, false);
  const DemSystem extrapolated = run(1, 300, true);
  using Field = std::vector<double> Particles::*;
  for (const Field field : {&Particles::position, &Particles::velocity}) {
    const std::vector<double>& a = held.particles().*field;
    const std::vector<double>& b = extrapolated.particles().*field;
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  }
  EXPECT_EQ(held.ledger().external_work_j, extrapolated.ledger().external_work_j);
}

TEST(FluidForceExtrapolation, TheLedgerBooksTheForceEachKickUsed) {
  // With no other force the external work is the kinetic energy gained. Per step the ledger's
  // trapezoid (F^n + F^{n+1})/2 . dx and Verlet's kinetic energy differ by
  // (F^n + F^{n+1})/2 (F^{n+1} - F^n) dt^2 / (4 m); the force only rises, so over the run
  // |difference| <= F_max (F_end - F_0) dt^2 / (4 m), held or extrapolated (4.6e-6 J/m here,
  // against 2.3 J/m of work). Booking the moved-on force in the drift's half instead would be off
  // by about the rate's dt / 2 times the distance moved, 1e-3 J/m.
  const double mass = 2800 * M_PI * 1e-6;
  for (const bool extrapolate : {false, true}) {
    const DemSystem s = run(5, 200, extrapolate);
    const double f_end = kForce0 + kForceRate * s.time_s();
    const double bound = f_end * (f_end - kForce0) * kDt * kDt / (4 * mass);
    EXPECT_NEAR(s.ledger().external_work_j, s.kinetic_energy(), bound) << extrapolate;
  }
}

TEST(FluidForceExtrapolation, AForceOfTheWrongSizeChangesNothing) {
  DemSystem s = run(5, 10, true);
  const std::vector<double> before = s.particles().external_force;
  for (int k = 0; k < 4; ++k) s.step(kDt);
  const std::vector<double> moved = s.particles().external_force;  // on the line
  ASSERT_NE(moved, before);
  s.begin_step(kDt);
  EXPECT_THROW(s.finish_step(kDt, std::vector<double>{1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(s.set_external_force(std::vector<double>{1.0}), std::invalid_argument);
  s.finish_step(kDt, force_at(s.time_s()));
  // The line through the last two accepted forces: the ramp's rate, not one from the refused.
  DemSystem fresh = run(5, 11, true);
  EXPECT_EQ(s.particles().external_force, fresh.particles().external_force);
  for (int k = 0; k < 3; ++k) {
    s.step(kDt);
    fresh.step(kDt);
  }
  EXPECT_EQ(s.particles().external_force, fresh.particles().external_force);
}

TEST(FluidForceExtrapolation, SwitchingOffDropsTheLine) {
  DemSystem s = run(5, 10, true);
  s.extrapolate_external_force(false);
  EXPECT_FALSE(s.external_force_extrapolated());
  const std::vector<double> before = s.particles().external_force;
  s.step(kDt);
  EXPECT_EQ(s.particles().external_force, before);  // held again
}

}  // namespace
}  // namespace rockcut::dem
