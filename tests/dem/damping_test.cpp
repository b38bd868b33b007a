// The damping models (core/local_damping.hpp, core/viscous_damping.hpp) and rolling resistance
// (core/rolling_resistance.hpp) on systems with closed-form answers: a bonded pair's free
// oscillation decays at the dashpots' damping ratio, a rigid chip keeps its momentum under
// dashpots, rolling resistance holds a moment up to mu_r R_r F_n, and the ledger closes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/dem_system.hpp"
#include "core/stability.hpp"
#include "core/viscous_damping.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

constexpr double kR = 3e-4, kRho = 2800, kKn = 7.25e9, kKs = 3.65e9;

// Two equal bonded discs, moving apart at +-v0 along x.
DemSystem bonded_pair(double zeta, double v0) {
  Particles p;
  p.add(0.0, 0.0, kR, kRho);
  p.add(2 * kR, 0.0, kR, kRho);
  p.velocity = {-v0, 0.0, v0, 0.0};
  BondSet bonds = test::bond_all_touching(p, {kKn, kKs, 1e9, 1e9});  // unbreakable here
  DemSettings s;
  s.contact = {kKn, kKs, 1.0, zeta, 0.0};
  return DemSystem(std::move(p), s, std::move(bonds));
}

double pair_mass() { return kRho * std::numbers::pi * kR * kR; }

TEST(ViscousDamping, RestitutionAndDampingRatioAreOneRelation) {
  // e = exp(-pi zeta / sqrt(1 - zeta^2)) both ways; e = 1 is no damping, and zeta 0.1 gives
  // e = 0.7292 (exp(-0.31574)).
  EXPECT_NEAR(restitution_from_damping_ratio(0.1), 0.729248, 1e-6);
  for (double e : {0.1, 0.5, 0.9, 1.0}) {
    EXPECT_NEAR(restitution_from_damping_ratio(damping_ratio_from_restitution(e)), e, 1e-14);
  }
  EXPECT_EQ(damping_ratio_from_restitution(1.0), 0.0);
}

TEST(ViscousDamping, ABondedPairsFreeOscillationDecaysAtZeta) {
  // The pair's relative coordinate is a damped oscillator of m_eff = m/2, k = K_n and
  // c = 2 zeta sqrt(m_eff K_n): successive peaks of the bond force fall by the logarithmic
  // decrement 2 pi zeta / sqrt(1 - zeta^2). 400 steps per period: the half-step velocity the
  // dashpot uses lags by dt/2, which shifts the measured zeta by O(omega dt / 2)^2 ~ 1e-4.
  for (double zeta : {0.02, 0.1, 0.3}) {
    DemSystem s = bonded_pair(zeta, 1e-3);
    const double omega = std::sqrt(kKn / (0.5 * pair_mass()));
    const double dt = 2 * std::numbers::pi / omega / 400;
    std::vector<double> peaks;
    double before = 0.0, now = 0.0;
    for (int k = 0; k < 400 * 6; ++k) {
      s.step(dt);
      const double f = -s.bonds().normal_force(0, s.particles());  // tension positive
      if (now > before && now > f && now > 0) peaks.push_back(now);
      before = now;
      now = f;
    }
    ASSERT_GE(peaks.size(), 4u) << zeta;
    const double decrement = std::log(peaks[0] / peaks[3]) / 3.0;
    const double measured = decrement / std::hypot(2 * std::numbers::pi, decrement);
    EXPECT_NEAR(measured / zeta, 1.0, 0.01) << "zeta " << zeta;
    // The ledger: what the dashpots took is what the pair lost, to 0.5 %.
    const double e0 = pair_mass() * 1e-6;  // 2 x m v0^2 / 2
    const double held = s.kinetic_energy() + s.strain_energy() + s.ledger().viscous_damping_j;
    EXPECT_NEAR(held / e0, 1.0, 5e-3) << "zeta " << zeta;
    EXPECT_GT(s.ledger().viscous_damping_j, 0.5 * e0) << "zeta " << zeta;
  }
}

TEST(ViscousDamping, TheLedgerSaysWhichDashpotsTookTheEnergy) {
  // The bonds' part of the dashpots' dissipation (viscous_damping_bonds_j): all of it for a bonded
  // pair's oscillation, none of it for two loose discs colliding, whose contact dashpots take
  // 1 - e^2 of the kinetic energy.
  DemSystem bonded = bonded_pair(0.1, 1e-3);
  for (int k = 0; k < 4000; ++k) bonded.step(2e-9);
  EXPECT_GT(bonded.ledger().viscous_damping_j, 0.0);
  EXPECT_EQ(bonded.ledger().viscous_damping_bonds_j, bonded.ledger().viscous_damping_j);

  Particles p;
  p.add(-kR - 1e-7, 0.0, kR, kRho);
  p.add(kR + 1e-7, 0.0, kR, kRho);
  const double v0 = 1e-2;
  p.velocity = {v0, 0.0, -v0, 0.0};
  DemSettings s;
  s.contact = {kKn, kKs, 1.0, 0.1, 0.0};
  DemSystem loose(std::move(p), s);
  for (int k = 0; k < 20000; ++k) loose.step(2e-9);
  ASSERT_LT(loose.particles().velocity[0], 0.0);  // they have bounced apart
  const double e0 = pair_mass() * v0 * v0, e = restitution_from_damping_ratio(0.1);
  // 0.5 %, the ledger's bound: the dashpot's work is booked with the half-step velocity over a
  // contact of about 370 steps (measured 0.17 % short).
  EXPECT_NEAR(loose.ledger().viscous_damping_j / ((1 - e * e) * e0), 1.0, 5e-3);
  EXPECT_EQ(loose.ledger().viscous_damping_bonds_j, 0.0);
}

TEST(ViscousDamping, ARigidlyMovingChipKeepsItsMomentumAndSpin) {
  // A bonded pair translating and spinning as one body: the dashpots see no relative velocity
  // (the spin terms of v_t cancel the orbit's), so nothing is dissipated but the tiny stretch the
  // centripetal force needs; local damping, which acts on each disc's total force, takes that
  // force's work every step instead.
  const double omega = 20.0, v = 0.5;  // rad/s, m/s
  auto spinning = [&](double zeta, double alpha) {
    Particles p;
    p.add(0.0, 0.0, kR, kRho);
    p.add(2 * kR, 0.0, kR, kRho);
    // About the midpoint (kR, 0): disc 0 moves down, disc 1 up, both spin at omega.
    p.velocity = {v, -omega * kR, v, omega * kR};
    p.angular_velocity = {omega, omega};
    BondSet bonds = test::bond_all_touching(p, {kKn, kKs, 1e9, 1e9});
    DemSettings s;
    s.contact = {kKn, kKs, 1.0, zeta, 0.0};
      s.local_damping = alpha;
    return DemSystem(std::move(p), s, std::move(bonds));
  };
  DemSystem dashpots = spinning(0.1, 0.0), local = spinning(0.0, 0.7);
  const double e0 = dashpots.kinetic_energy();
  const double dt = 1e-8;
  for (int k = 0; k < 20000; ++k) {  // 0.2 ms: 4 mrad of turn
    dashpots.step(dt);
    local.step(dt);
  }
  const auto momentum_x = [](const DemSystem& s) {
    const Particles& p = s.particles();
    return p.velocity[0] / p.inv_mass[0] + p.velocity[2] / p.inv_mass[1];
  };
  EXPECT_NEAR(momentum_x(dashpots) / (2 * pair_mass() * v), 1.0, 1e-9);
  EXPECT_LT(dashpots.ledger().viscous_damping_j, 1e-6 * e0);
  EXPECT_NEAR(dashpots.kinetic_energy() / e0, 1.0, 1e-6);
  // Local damping on the same chip takes a measurable share: it is no model of a flying chip.
  EXPECT_GT(local.ledger().damping_j, 100 * dashpots.ledger().viscous_damping_j);
}

TEST(ViscousDamping, TheCriticalStepShrinksByTheCentralDifferenceFactor) {
  Particles p;
  p.add(0.0, 0.0, kR, kRho);
  const CriticalStep bare = critical_step(p, kKn, kKs);
  const CriticalStep damped = critical_step(p, kKn, kKs, 0.2);
  EXPECT_NEAR(damped.dt_s / bare.dt_s, std::sqrt(1.04) - 0.2, 1e-15);
  EXPECT_NE(damped.detail.find("zeta"), std::string::npos) << damped.detail;
  // Rolling springs double the rotational stiffness against a wall: the rotation mode binds.
  const CriticalStep rolling = critical_step(p, kKn, kKn, 0.0, true);
  EXPECT_NE(rolling.detail.find("2 k_s r^2"), std::string::npos) << rolling.detail;
}

// A disc pressed on a frictionless floor by gravity, spun, and stopped by rolling resistance
// alone. Closed form: the rolling spring's moment is
// capped at mu_r R_r F_n (R_r = r against a wall), so a disc spinning on the floor decelerates at
// mu_r r m g / I once the spring has yielded, and its spin energy goes to the rolling ledger and
// to friction.
TEST(RollingResistance, ASpinningDiscOnAFloorStopsAtTheRateTheLimitSets) {
  const double mu_r = 0.2, g = 1000.0;  // a strong gravity: a firm contact in few steps
  Particles p;
  p.add(0.0, kR, kR, kRho);
  DemSettings s;
  s.gravity_y_m_s2 = -g;
  // Frictionless floor: the disc spins in place, only the rolling spring resists.
  s.contact = {kKn, kKs, 0.0, 0.0, mu_r};
  WallSet walls;
  walls.add_body("floor", {-0.01, 0.0, 0.01, 0.0}, false, 0.0, 0.0);
  DemSystem settled(std::move(p), s, BondSet{}, std::move(walls));
  const double m = pair_mass(), inertia = 0.5 * m * kR * kR;
  const double dt = 0.1 * std::sqrt(m / kKn);
  // Settle under gravity (it bounces on the stiff floor at first): give it time, then spin it.
  for (int k = 0; k < 200000; ++k) settled.step(dt);
  // The expected deceleration from the normal force the floor now carries (m g at rest).
  const double limit = mu_r * kR * m * g;
  const double decel = limit / inertia;  // rad/s^2
  // Spin: restart with the settled state and an angular velocity.
  Particles spun = settled.particles();
  const double w0 = 50.0;
  spun.angular_velocity[0] = w0;
  WallSet floor;
  floor.add_body("floor", {-0.01, 0.0, 0.01, 0.0}, false, 0.0, 0.0);
  DemSystem disc(std::move(spun), s, BondSet{}, std::move(floor));
  const double t_stop = w0 / decel;
  const int steps = static_cast<int>(0.5 * t_stop / dt);
  for (int k = 0; k < steps; ++k) disc.step(dt);
  // Halfway to the stop, the spin is half of w0 (the spring's elastic wind-up, M/k_r, is a
  // rotation of mu_r F_n r / (k_s r^2) ~ 1e-9 rad: negligible).
  EXPECT_NEAR(disc.particles().angular_velocity[0] / w0, 0.5, 0.01);
  EXPECT_GT(disc.ledger().rolling_j, 0.0);
  // The ledger: the spin energy lost went to the rolling springs (the floor is frictionless).
  const double lost = 0.5 * inertia * (w0 * w0 - std::pow(disc.particles().angular_velocity[0], 2));
  EXPECT_NEAR(disc.ledger().rolling_j / lost, 1.0, 5e-3);
}

}  // namespace
}  // namespace rockcut::dem

namespace rockcut::dem {
namespace {

// A fixed group (dem.fixed_base_height_m: the rock mass under a cut block) stays at rest while a
// disc bonded to it oscillates against it, and the ledger still closes: the held discs do no work.
TEST(FixedGroup, HeldDiscsStayAtRestAndTheLedgerCloses) {
  for (double zeta : {0.0, 0.1}) {
    Particles p;
    p.add(0.0, 0.0, kR, kRho);
    p.add(2 * kR, 0.0, kR, kRho);
    p.velocity = {0.0, 0.0, 1e-3, 5e-4};
    p.angular_velocity = {0.0, 3.0};
    BondSet bonds = test::bond_all_touching(p, {kKn, kKs, 1e9, 1e9});
    DemSettings s;
    s.contact = {kKn, kKs, 1.0, zeta, 0.0};
      DemSystem sys(std::move(p), s, std::move(bonds));
    const double e0 = sys.kinetic_energy();
    sys.add_clamped_group({0}, 0.0, /*fixed=*/true);
    const double dt = 0.05 * std::sqrt(pair_mass() / kKn);
    for (int k = 0; k < 20000; ++k) sys.step(dt);
    const Particles& q = sys.particles();
    EXPECT_EQ(q.position[0], 0.0);
    EXPECT_EQ(q.position[1], 0.0);
    EXPECT_EQ(q.velocity[0], 0.0);
    EXPECT_EQ(q.angular_velocity[0], 0.0);
    const double held = sys.kinetic_energy() + sys.strain_energy() + sys.ledger().viscous_damping_j;
    EXPECT_NEAR(held / e0, 1.0, 5e-3) << "zeta " << zeta;
    if (zeta > 0) {
      EXPECT_GT(sys.ledger().viscous_damping_j, 0.5 * e0);
    }
  }
}

}  // namespace
}  // namespace rockcut::dem
