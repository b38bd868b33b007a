// Rigid walls and the tool: the force on a body is the sum of its contact forces.
#include <gtest/gtest.h>

#include "core/dem_system.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

TEST(Walls, ToolForceEqualsTheSumOfItsContactForces) {
  // A loose row of discs pushed by a moving vertical plate into a fixed wall.
  Particles p;
  for (int i = 0; i < 5; ++i) p.add(0.0021 * i + 0.001, 0.001, 0.001, 2800);
  DemSettings s;
  s.contact = {1e7, 2.5e7, 0.5};
  s.local_damping = 0.3;
  WallSet walls;
  walls.add_body("tool", {-0.0001, -0.01, -0.0001, 0.01}, false, 0.05, 0.0);
  walls.add_body("wall", {0.0113, -0.01, 0.0113, 0.01}, false, 0.0, 0.0);
  DemSystem system(std::move(p), s, {}, std::move(walls));
  bool loaded = false;
  for (int k = 0; k < 200000; ++k) {
    system.step(2e-7);
    const WallBody& tool = system.walls().bodies()[0];
    if (tool.force_x == 0.0) continue;
    loaded = true;
    // Independent sum: the contact force of the plate on every disc it overlaps.
    double sum = 0.0;
    const auto& x = system.particles().position;
    for (std::size_t i = 0; i < system.particles().size(); ++i) {
      const double overlap = 0.001 - (x[2 * i] - (-0.0001 + tool.offset_x));
      if (overlap > 0) sum += 1e7 * overlap;
    }
    ASSERT_NEAR(tool.force_x, -sum, 1e-9 * std::abs(sum)) << "step " << k;
    if (system.time_s() > 0.02) break;
  }
  EXPECT_TRUE(loaded);
}

TEST(Walls, DiscRestsOnAFloorUnderGravity) {
  Particles p;
  p.add(0.0, 0.0012, 0.001, 2800);
  DemSettings s;
  s.contact = {1e6, 1e6, 0.5};
  s.gravity_y_m_s2 = -9.81;
  s.local_damping = 0.7;
  WallSet walls;
  walls.add_body("floor", {-1.0, 0.0, 1.0, 0.0}, false, 0.0, 0.0);
  DemSystem system(std::move(p), s, {}, std::move(walls));
  for (int k = 0; k < 200000; ++k) system.step(1e-6);
  const double m = 2800 * M_PI * 1e-6;
  // At rest the floor carries the weight and the overlap is m g / k (damping removes motion).
  EXPECT_NEAR(system.walls().bodies()[0].force_y, -m * 9.81, 1e-6 * m * 9.81);
  EXPECT_NEAR(system.particles().position[1], 0.001 - m * 9.81 / 1e6, 1e-9);
}

}  // namespace
}  // namespace rockcut::dem
