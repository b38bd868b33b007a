// Velocity Verlet (paper eqs. 5-8) and its split into two halves around the fluid exchange.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/dem_system.hpp"
#include "core/lattice.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

using test::two_discs;

TEST(Verlet, ExactForConstantAcceleration) {
  DemSettings settings;
  settings.gravity_y_m_s2 = -9.81;
  Particles p = two_discs();
  p.velocity = {0.3, 1.0, 0.3, 1.0};
  const std::vector<double> x0 = p.position;
  DemSystem s(std::move(p), settings);
  const double dt = 1e-4;
  for (int k = 0; k < 1000; ++k) s.step(dt);
  const double t = s.time_s();
  for (int i = 0; i < 2; ++i) {
    // Round-off only: 1000 steps * eps * |x| ~ 1e-15 m.
    EXPECT_NEAR(s.particles().position[2 * i], x0[2 * i] + 0.3 * t, 1e-14);
    EXPECT_NEAR(s.particles().position[2 * i + 1], 1.0 * t - 0.5 * 9.81 * t * t, 1e-14);
    EXPECT_NEAR(s.particles().velocity[2 * i + 1], 1.0 - 9.81 * t, 1e-13);
  }
}

TEST(Verlet, SplitStepEqualsFullStepBitForBit) {
  // begin_step + (internal forces while the fluid works) + finish_step must be the same
  // arithmetic as step(): the coupling may not change the DEM's answer.
  DemSettings settings;
  settings.gravity_y_m_s2 = -9.81;
  const std::vector<double> external = {0.5, -0.25, -1.0, 2.0};
  DemSystem full(two_discs(), settings), split(two_discs(), settings);
  full.set_external_force(external);
  split.set_external_force(external);
  for (int k = 0; k < 100; ++k) {
    full.step(1e-4);
    split.begin_step(1e-4);
    if (k % 2) split.compute_internal_forces();  // with and without the overlap
    split.finish_step(1e-4, external);
  }
  EXPECT_EQ(std::memcmp(full.particles().position.data(), split.particles().position.data(),
                        4 * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(full.particles().velocity.data(), split.particles().velocity.data(),
                        4 * sizeof(double)), 0);
}

TEST(Verlet, ExternalForceActsFromTheFirstStep) {
  Particles p = two_discs();
  const double m = 2800 * M_PI * 1e-6;
  DemSystem s(std::move(p), {});
  s.set_external_force(std::vector<double>{m, 0.0, 0.0, -2 * m});  // a = (1, 0) and (0, -2)
  s.step(0.01);
  EXPECT_NEAR(s.particles().velocity[0], 0.01, 1e-15);
  EXPECT_NEAR(s.particles().velocity[3], -0.02, 1e-15);
  EXPECT_NEAR(s.particles().position[0], 0.5 * 0.01 * 0.01, 1e-16);
}

TEST(Verlet, WrongExternalForceSizeIsRefused) {
  DemSystem s(two_discs(), {});
  EXPECT_THROW(s.set_external_force(std::vector<double>{1.0}), std::invalid_argument);
}

TEST(Verlet, KineticEnergyOfKnownMotion) {
  Particles p = two_discs();
  p.velocity = {1.0, 0.0, 0.0, 2.0};
  const double m = 2800 * M_PI * 1e-6;  // per metre of thickness
  DemSystem s(std::move(p), {});
  EXPECT_NEAR(s.kinetic_energy(), 0.5 * m * 1.0 + 0.5 * m * 4.0, 1e-15);
}

}  // namespace
}  // namespace rockcut::dem

namespace rockcut::dem {
namespace {

TEST(PrescribedMotion, UniformCompressionScalesPositionsExactly) {
  // v = eps_rate (x - origin): each step multiplies the offset by (1 + eps_rate dt) exactly as
  // forward Euler on the field, so after n steps offset = x0 (1 + eps_rate dt)^n.
  LatticeSpec spec;
  spec.nx = 3;
  spec.ny = 3;
  spec.spacing_m = 0.01;
  spec.radius_m = 0.001;
  DemSettings settings;
  PrescribedMotion m;
  m.strain_rate_xx_per_s = -2.0;
  m.strain_rate_yy_per_s = -1.0;
  m.end_time_s = 0.01;  // 100 steps of 1e-4, then at rest
  settings.prescribed_motion = m;
  Particles p = make_lattice(spec);
  const std::vector<double> x0 = p.position;
  DemSystem s(std::move(p), settings);
  s.set_external_force(std::vector<double>(18, 5.0));  // ignored: no dynamics
  for (int k = 0; k < 150; ++k) s.step(1e-4);
  for (std::size_t i = 0; i < 9; ++i) {
    EXPECT_NEAR(s.particles().position[2 * i], x0[2 * i] * std::pow(1 - 2e-4, 100), 1e-15);
    EXPECT_NEAR(s.particles().position[2 * i + 1], x0[2 * i + 1] * std::pow(1 - 1e-4, 100), 1e-15);
  }
  EXPECT_EQ(s.particles().velocity[2 * 8], 0.0);  // after end_time_s
}

}  // namespace
}  // namespace rockcut::dem
