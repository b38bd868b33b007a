// Contact law of DESIGN section 4 against the analytical two-disc collision.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/dem_system.hpp"

namespace rockcut::dem {
namespace {

struct Collision {
  double duration_s;
  double restitution;
};

// Two equal discs approach head-on at +-v0 and separate again.
Collision collide(double k, double mu, double ks) {
  const double r = 1e-3, v0 = 0.1, rho = 2800;
  Particles p;
  p.add(-r - 1e-5, 0.0, r, rho);
  p.add(r + 1e-5, 0.0, r, rho);
  p.velocity = {v0, 0.0, -v0, 0.0};
  DemSettings s;
  s.contact = {k, ks, mu};
  const double m = rho * std::numbers::pi * r * r;
  const double duration = std::numbers::pi * std::sqrt(0.5 * m / k);  // pi sqrt(m*/k), m* = m/2
  const double dt = duration / 2000;
  DemSystem system(std::move(p), s);
  double contact_start = -1, contact_end = -1;
  for (int step = 0; step < 20000 && contact_end < 0; ++step) {
    system.step(dt);
    const auto& x = system.particles().position;
    const bool touching = x[2] - x[0] < 2 * r;
    if (touching && contact_start < 0) contact_start = system.time_s() - 0.5 * dt;
    if (!touching && contact_start >= 0) contact_end = system.time_s() - 0.5 * dt;
  }
  const double v_after = system.particles().velocity[2] - system.particles().velocity[0];
  return {contact_end - contact_start, v_after / (2 * v0)};
}

TEST(ContactLaw, TwoDiscCollisionDurationAndRestitution) {
  const double k = 1e7, r = 1e-3, m = 2800 * std::numbers::pi * r * r;
  const Collision c = collide(k, 0.5, 2.5e7);
  const double expected = std::numbers::pi * std::sqrt(0.5 * m / k);
  // 0.5 %: the contact is sampled at 2000 steps per duration (0.05 % resolution); velocity
  // Verlet's phase error at this step is O((omega dt)^2) ~ 1e-6.
  EXPECT_NEAR(c.duration_s / expected, 1.0, 0.005);
  EXPECT_NEAR(c.restitution, 1.0, 0.005);
}

TEST(ContactLaw, HeadOnCollisionCreatesNoSpin) {
  Particles p;
  p.add(-1.001e-3, 0, 1e-3, 2800);
  p.add(1.001e-3, 0, 1e-3, 2800);
  p.velocity = {0.1, 0, -0.1, 0};
  DemSettings s;
  s.contact = {1e7, 2.5e7, 0.5};
  DemSystem system(std::move(p), s);
  for (int k = 0; k < 2000; ++k) system.step(1e-7);
  EXPECT_EQ(system.particles().angular_velocity[0], 0.0);
  EXPECT_EQ(system.particles().angular_velocity[1], 0.0);
}

TEST(ContactLaw, SlidingIsLimitedByCoulomb) {
  // A disc pressed on a fixed wall by gravity and dragged sideways: once sliding, the tangential
  // force equals mu * F_n.
  Particles p;
  const double r = 1e-3;
  const double weight = 2800 * std::numbers::pi * r * r * 9.81;
  p.add(0.0, r - weight / 1e7, r, 2800);  // at its static overlap: no bouncing
  p.velocity = {0.01, 0.0};
  DemSettings s;
  s.contact = {1e7, 1e7, 0.3};
  s.gravity_y_m_s2 = -9.81;
  s.local_damping = 0.0;
  WallSet walls;
  walls.add_body("floor", {-1.0, 0.0, 1.0, 0.0}, false, 0.0, 0.0);
  DemSystem system(std::move(p), s, {}, std::move(walls));
  // Drag with a constant horizontal force well above mu m g: the disc slides and rolls.
  const double m = 2800 * std::numbers::pi * r * r;
  const std::vector<double> drag = {2.0 * 0.3 * m * 9.81, 0.0};
  system.set_external_force(drag);
  for (int k = 0; k < 40000; ++k) system.step(1e-6);
  const auto& floor = system.walls().bodies()[0];
  // The floor carries the normal load m g and at most mu m g sideways (1e-3: the normal
  // force still oscillates a little around m g).
  EXPECT_NEAR(-floor.force_y / (m * 9.81), 1.0, 1e-2);
  EXPECT_LE(std::abs(floor.force_x), 0.3 * std::abs(floor.force_y) * (1 + 1e-12));
}

}  // namespace
}  // namespace rockcut::dem
