// The coupling lag's energy taken out again (core/fluid_force_passivity.hpp). Each disc hangs on
// a "pore fluid" spring F = -k (x - x_0) that, like the fluid, is evaluated only at the exchanges
// and held or extrapolated between them, driven as the coupler drives the DEM: N - 1 full steps,
// then a split step completed with the spring's force at its end. The spring's stored energy
// k |x - x_0|^2 / 2 plays the fluid's: the trapezoid of its forces is exactly its work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/dem_system.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

using test::two_discs;

constexpr double kSpringDt = 1e-4;
constexpr double kSpringV0 = 0.05;       // [m/s] disc 0 in x, disc 1 in y at t = 0
constexpr double kStepsPerPeriod = 400;  // 50 exchanges a period at N = 8

struct Oscillator {
  DemSystem system;
  std::vector<double> rest;   // x_0
  double stiffness = 0.0;     // k [N/m^2]
  double max_energy_j = 0.0;  // the largest kinetic + spring energy seen at an exchange

  std::vector<double> force() const {
    const std::vector<double>& x = system.particles().position;
    std::vector<double> f(x.size());
    for (std::size_t k = 0; k < x.size(); ++k) f[k] = -stiffness * (x[k] - rest[k]);
    return f;
  }
  double spring_energy_j() const {
    const std::vector<double>& x = system.particles().position;
    double e = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k)
      e += 0.5 * stiffness * (x[k] - rest[k]) * (x[k] - rest[k]);
    return e;
  }
  double energy_j() const { return system.kinetic_energy() + spring_energy_j(); }
};

Oscillator make_oscillator(bool extrapolate, bool passive) {
  Oscillator o{DemSystem(two_discs(), {}), {}, 0.0, 0.0};
  const double mass = 1.0 / o.system.particles().inv_mass[0];
  const double omega = 2 * M_PI / (kStepsPerPeriod * kSpringDt);
  o.stiffness = mass * omega * omega;
  o.rest = o.system.particles().position;
  o.system.particles_for_driving().velocity = {kSpringV0, 0.0, 0.0, kSpringV0};
  o.system.extrapolate_external_force(extrapolate);
  o.system.correct_lag_passively(passive);
  o.system.set_external_force(o.force());
  o.max_energy_j = o.energy_j();
  return o;
}

void run_exchanges(Oscillator& o, unsigned n, unsigned exchanges) {
  for (unsigned m = 0; m < exchanges; ++m) {
    for (unsigned k = 0; k + 1 < n; ++k) o.system.step(kSpringDt);
    o.system.begin_step(kSpringDt);
    o.system.finish_step(kSpringDt, o.force());
    o.max_energy_j = std::max(o.max_energy_j, o.energy_j());
  }
}

// Twenty periods at N = 8: 1000 exchanges.
constexpr unsigned kLagN = 8;
constexpr unsigned kLagExchanges = 20 * 400 / kLagN;

TEST(FluidForcePassivity, TheHeldSpringGrowsWithoutIt) {
  // The held force lags by up to N dt: a negative damping c = k (N - 1) dt / 2 (the trapezoid
  // over the interval against the held force), energy growing as exp(c t / m) =
  // exp(omega^2 (N - 1) dt t / 2): e^8.7 over these twenty periods. At least half of that in
  // the exponent (the growth is first order in omega N dt = 0.13).
  Oscillator o = make_oscillator(false, false);
  const double e0 = o.energy_j();
  run_exchanges(o, kLagN, kLagExchanges);
  const double omega = 2 * M_PI / (kStepsPerPeriod * kSpringDt);
  const double exponent =
      omega * omega * (kLagN - 1) * kSpringDt * (kLagExchanges * kLagN * kSpringDt) / 2;
  EXPECT_GT(std::log(o.energy_j() / e0), 0.5 * exponent);
}

TEST(FluidForcePassivity, TheObserverTakesOutWhatTheLagPutsIn) {
  // With the observer the interface gives the discs no more than the spring's own energy: at any
  // exchange the energy exceeds E_0 by at most one interval's generation, k |dx|^2 (N - 1) / (2N)
  // <= (omega N dt)^2 E_0 (the controller takes it out in the next interval), and after twenty
  // periods it is E_0 within the same. The controller's dashpot takes what the lag put in: the
  // uncorrected run gains e^8.7 (above).
  for (const bool extrapolate : {false, true}) {
    Oscillator o = make_oscillator(extrapolate, true);
    const double e0 = o.energy_j();
    run_exchanges(o, kLagN, kLagExchanges);
    const double omega = 2 * M_PI / (kStepsPerPeriod * kSpringDt);
    const double interval = std::pow(omega * kLagN * kSpringDt, 2);  // 0.0158
    EXPECT_LT(o.max_energy_j / e0 - 1, interval) << extrapolate;
    EXPECT_NEAR(o.energy_j() / e0, 1.0, interval) << extrapolate;
    EXPECT_GT(o.system.ledger().lag_correction_j, 0.0) << extrapolate;
  }
}

TEST(FluidForcePassivity, TheLedgerBooksTheDashpotsWork) {
  // Given = held with the correction as a sink: kinetic energy + the lag's correction = E_0 +
  // the external work. The ledger's trapezoid and Verlet's kinetic energy differ per step by
  // (F^n + F^{n+1})/2 (F^{n+1} - F^n) dt^2 / (4m), which for the spring telescopes to at most
  // F_max^2 dt^2 / (8m) = E_0 (omega dt)^2 / 4 at any time, and as much again for the dashpot:
  // (omega dt)^2 / 2 of the throughput (1.2e-4; measured 5e-6).
  Oscillator o = make_oscillator(false, true);
  const double e0 = o.system.kinetic_energy();
  run_exchanges(o, kLagN, kLagExchanges);
  const EnergyLedger& l = o.system.ledger();
  const double throughput = e0 + std::abs(l.external_work_j);
  const double omega_dt = 2 * M_PI / kStepsPerPeriod;
  EXPECT_NEAR(e0 + l.external_work_j, o.system.kinetic_energy() + l.lag_correction_j,
              0.5 * omega_dt * omega_dt * throughput);
}

TEST(FluidForcePassivity, AtOneStepPerExchangeNothingChangesABit) {
  // N = 1: the applied work is the trapezoid itself, and the controller stays off.
  Oscillator off = make_oscillator(true, false);
  Oscillator on = make_oscillator(true, true);
  run_exchanges(off, 1, 800);
  run_exchanges(on, 1, 800);
  using Field = std::vector<double> Particles::*;
  for (const Field field : {&Particles::position, &Particles::velocity}) {
    const std::vector<double>& a = off.system.particles().*field;
    const std::vector<double>& b = on.system.particles().*field;
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  }
  EXPECT_EQ(on.system.ledger().lag_correction_j, 0.0);
}

TEST(FluidForcePassivity, ARestoredStateGoesOnWithTheSameBits) {
  // The observer's residuals and the dashpot's coefficients are state: a run saved and loaded
  // between two exchanges continues bit for bit.
  Oscillator whole = make_oscillator(true, true);
  run_exchanges(whole, kLagN, 200);
  Oscillator first = make_oscillator(true, true);
  run_exchanges(first, kLagN, 100);
  state::StateArchive a;
  first.system.save_state(a);
  Oscillator second = make_oscillator(true, true);
  second.system.load_state(a);
  run_exchanges(second, kLagN, 100);
  const std::vector<double>& x = whole.system.particles().position;
  const std::vector<double>& y = second.system.particles().position;
  EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(double)), 0);
  EXPECT_EQ(whole.system.ledger().lag_correction_j, second.system.ledger().lag_correction_j);
}

}  // namespace
}  // namespace rockcut::dem
