// Each grain's own fluid stiffness applied between exchanges (core/fluid_self_stiffness.hpp). As
// in fluid_force_passivity_test, each disc hangs on a "pore fluid" spring F = -k (x - x_0)
// evaluated only at the exchanges, driven as the coupler drives the DEM: N - 1 full steps, then a
// split step completed with the spring's force at its end. Here the exchange also sends the
// spring's own stiffness, K_ii = k (xx, yy; xy 0): a spring that is all self stiffness, so the
// DEM applies -k (x - x_0) at every step, and the lagged run must follow the unlagged one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "core/dem_system.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

constexpr double kSelfDt = 1e-4;
constexpr double kSelfV0 = 0.05;            // [m/s] disc 0 in x, disc 1 in y at t = 0
constexpr double kSelfStepsPerPeriod = 400;

struct SelfSpring {
  DemSystem system;
  std::vector<double> rest;  // x_0
  double stiffness = 0.0;    // k [N/m^2]

  std::vector<double> force() const {
    const std::vector<double>& x = system.particles().position;
    std::vector<double> f(x.size());
    for (std::size_t k = 0; k < x.size(); ++k) f[k] = -stiffness * (x[k] - rest[k]);
    return f;
  }
  std::vector<double> self() const {
    std::vector<double> k(3 * system.particles().size(), 0.0);
    for (std::size_t i = 0; i < system.particles().size(); ++i) {
      k[3 * i] = stiffness;
      k[3 * i + 2] = stiffness;
    }
    return k;
  }
  double energy_j() const {
    const std::vector<double>& x = system.particles().position;
    double e = system.kinetic_energy();
    for (std::size_t k = 0; k < x.size(); ++k)
      e += 0.5 * stiffness * (x[k] - rest[k]) * (x[k] - rest[k]);
    return e;
  }
};

SelfSpring make_self_spring(bool extrapolate, bool self) {
  SelfSpring o{DemSystem(test::two_discs(), {}), {}, 0.0};
  const double mass = 1.0 / o.system.particles().inv_mass[0];
  const double omega = 2 * M_PI / (kSelfStepsPerPeriod * kSelfDt);
  o.stiffness = mass * omega * omega;
  o.rest = o.system.particles().position;
  o.system.particles_for_driving().velocity = {kSelfV0, 0.0, 0.0, kSelfV0};
  o.system.extrapolate_external_force(extrapolate);
  o.system.stiffen_external_force(self);
  o.system.set_external_force(o.force(), self ? o.self() : std::vector<double>{});
  return o;
}

void run_self_exchanges(SelfSpring& o, unsigned n, unsigned exchanges, bool self) {
  for (unsigned m = 0; m < exchanges; ++m) {
    for (unsigned k = 0; k + 1 < n; ++k) o.system.step(kSelfDt);
    o.system.begin_step(kSelfDt);
    o.system.finish_step(kSelfDt, o.force(), self ? o.self() : std::vector<double>{});
  }
}

constexpr unsigned kSelfN = 8;
constexpr unsigned kSelfExchanges = 20 * 400 / kSelfN;  // twenty periods

TEST(FluidSelfStiffness, ALaggedSpringThatIsAllSelfStiffnessFollowsTheUnlaggedOne) {
  // Without it the held spring's energy grows e^8.7 over these twenty periods
  // (fluid_force_passivity_test). With it the force each step uses is F^m - k (x - x^m) =
  // -k (x - x_0), the N = 1 run's force, up to rounding: held or extrapolated (whose rate the
  // self answer cancels: r' = r + k (x^m - x^{m-1}) / dt_m = 0), N = 8 stays within 1e-9 of the
  // amplitude of N = 1's positions after 8000 steps (the rounding of x - x^m, ~1e-16 of x, over
  // the steps; a force lagged by one step would move them by 1e-2), and its energy is N = 1's.
  SelfSpring unlagged = make_self_spring(false, false);
  run_self_exchanges(unlagged, 1, kSelfExchanges * kSelfN, false);
  const double amplitude = kSelfV0 * kSelfStepsPerPeriod * kSelfDt / (2 * M_PI);
  for (const bool extrapolate : {false, true}) {
    SelfSpring lagged = make_self_spring(extrapolate, true);
    const double e0 = lagged.energy_j();
    run_self_exchanges(lagged, kSelfN, kSelfExchanges, true);
    const std::vector<double>& a = unlagged.system.particles().position;
    const std::vector<double>& b = lagged.system.particles().position;
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_NEAR(a[k], b[k], 1e-9 * amplitude) << "extrapolate " << extrapolate << ", " << k;
    }
    EXPECT_NEAR(lagged.energy_j() / e0, unlagged.energy_j() / e0, 1e-6) << extrapolate;
  }
}

TEST(FluidSelfStiffness, TheLedgerBooksTheForceEachKickUsed) {
  // Kinetic energy = E_0 + the external work, to the trapezoid's telescoping rest
  // (fluid_force_passivity_test, "TheLedgerBooksTheDashpotsWork"): (omega dt)^2 / 4 of the
  // throughput.
  // The spring starts at rest length (F^0 = 0): the self stiffness alone must start the booking.
  SelfSpring o = make_self_spring(true, true);
  const double e0 = o.system.kinetic_energy();
  run_self_exchanges(o, kSelfN, kSelfExchanges, true);
  const EnergyLedger& l = o.system.ledger();
  const double throughput = e0 + std::abs(l.external_work_j);
  const double omega_dt = 2 * M_PI / kSelfStepsPerPeriod;
  EXPECT_NEAR(e0 + l.external_work_j, o.system.kinetic_energy(),
              0.25 * omega_dt * omega_dt * throughput);
}

TEST(FluidSelfStiffness, AtOneStepPerExchangeNothingChangesABit) {
  // N = 1: every step ends at an exchange that replaces the force, so the self stiffness is never
  // used on a step's kick.
  SelfSpring off = make_self_spring(true, false);
  SelfSpring on = make_self_spring(true, true);
  run_self_exchanges(off, 1, 800, false);
  run_self_exchanges(on, 1, 800, true);
  using Field = std::vector<double> Particles::*;
  for (const Field field : {&Particles::position, &Particles::velocity}) {
    const std::vector<double>& a = off.system.particles().*field;
    const std::vector<double>& b = on.system.particles().*field;
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  }
}

TEST(FluidSelfStiffness, AWrongSizeIsRefusedAndChangesNothing) {
  SelfSpring o = make_self_spring(true, true);
  run_self_exchanges(o, kSelfN, 10, true);
  for (unsigned k = 0; k + 1 < kSelfN; ++k) o.system.step(kSelfDt);
  o.system.begin_step(kSelfDt);
  const std::vector<double> x = o.system.particles().position;
  const std::vector<double> v = o.system.particles().velocity;
  const std::vector<double> fe = o.system.particles().external_force;
  const std::vector<double> k_before = o.system.fluid_self_stiffness().k_pa;
  const std::vector<double> short_k(3, 1.0);
  EXPECT_THROW(o.system.finish_step(kSelfDt, o.force(), short_k), std::invalid_argument);
  EXPECT_EQ(o.system.particles().position, x);
  EXPECT_EQ(o.system.particles().velocity, v);
  EXPECT_EQ(o.system.particles().external_force, fe);
  EXPECT_EQ(o.system.fluid_self_stiffness().k_pa, k_before);
  // The right size then completes the step as if nothing had happened.
  EXPECT_NO_THROW(o.system.finish_step(kSelfDt, o.force(), o.self()));
}

TEST(FluidSelfStiffness, ARestoredStateGoesOnWithTheSameBits) {
  // K_ii, x^m and t_m are state: a run saved and loaded between two exchanges continues bit for
  // bit.
  SelfSpring whole = make_self_spring(true, true);
  run_self_exchanges(whole, kSelfN, 200, true);
  SelfSpring first = make_self_spring(true, true);
  run_self_exchanges(first, kSelfN, 100, true);
  state::StateArchive a;
  first.system.save_state(a);
  SelfSpring second = make_self_spring(true, false);
  second.system.load_state(a);
  EXPECT_TRUE(second.system.fluid_self_stiffness().on);
  run_self_exchanges(second, kSelfN, 100, true);
  using Field = std::vector<double> Particles::*;
  for (const Field field : {&Particles::position, &Particles::velocity}) {
    const std::vector<double>& x = whole.system.particles().*field;
    const std::vector<double>& y = second.system.particles().*field;
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(double)), 0);
  }
}

}  // namespace
}  // namespace rockcut::dem
