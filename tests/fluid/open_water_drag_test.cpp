// The open water's drag on the grains that meet it (sp/open_water_drag.hpp, fluid.open_water_drag):
// the law itself, and which grains the pore-pressure model applies it to.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fluid/sp_test_support.hpp"
#include "sp/open_water_drag.hpp"

namespace rockcut::fluid::test {
namespace {

TEST(OpenWaterDrag, TheLawGivesTheCylindersDragByHand) {
  // The grain the paper-scale cut throws at 0 m: r = 0.34 mm at 9.4 m/s in seawater (1025 kg/m^3,
  // mu 1e-3 Pa s). By hand: Re = 1025 * 9.4 * 6.8e-4 / 1e-3 = 6551.8, Re^(2/3) = 350.139,
  // C_d = 1.028560, F = 0.5 * 1025 * 1.028560 * 6.8e-4 * 9.4^2 = 31.673 N/m. To 1e-4: the hand
  // figures' five digits.
  double fx = 0.0, fy = 0.0;
  sp::add_open_water_drag(0.00034, 9.4, 0.0, 1025.0, 1e-3, fx, fy);
  EXPECT_NEAR(fx, -31.673, 31.673 * 1e-4);
  EXPECT_EQ(fy, 0.0);
  EXPECT_NEAR(sp::cylinder_drag_coefficient(6551.8), 1.028560, 1e-6);
  // It opposes the motion in any direction and does not depend on it: the same speed along a
  // diagonal gives the same magnitude, along -v.
  double gx = 0.0, gy = 0.0;
  const double s = 9.4 / std::sqrt(2.0);
  sp::add_open_water_drag(0.00034, -s, s, 1025.0, 1e-3, gx, gy);
  EXPECT_NEAR(std::hypot(gx, gy), std::abs(fx), std::abs(fx) * 1e-12);
  EXPECT_NEAR(gx, -gy, std::abs(fx) * 1e-12);
  EXPECT_GT(gx, 0.0);
  // At rest, nothing; it adds to what is there.
  double hx = 1.0, hy = -2.0;
  sp::add_open_water_drag(0.00034, 0.0, 0.0, 1025.0, 1e-3, hx, hy);
  EXPECT_EQ(hx, 1.0);
  EXPECT_EQ(hy, -2.0);
  // Above Re ~ 1e3 the force goes nearly as v^2 (C_d -> 1), below as v^(4/3) (C_d ~ 10
  // Re^(-2/3)): doubling the speed at Re 6552 gives 4 C_d(2 Re) / C_d(Re) = 3.959 times.
  double f2x = 0.0, f2y = 0.0;
  sp::add_open_water_drag(0.00034, 18.8, 0.0, 1025.0, 1e-3, f2x, f2y);
  EXPECT_NEAR(f2x / fx,
              4.0 * sp::cylinder_drag_coefficient(2 * 6551.8) / sp::cylinder_drag_coefficient(6551.8),
              1e-9);
  EXPECT_NEAR(f2x / fx, 3.959, 0.001);
}

// A random packing at rest, and one grain of it moved off, far from the rest and moving: only
// drained grains feel the drag, and the force and power the model reports are the law's.
TEST(OpenWaterDrag, OnlyTheDrainedGrainsFeelItInTheModel) {
  Particles p = random_packing();
  // The thrown grain: 20 mm beyond the packing's right side (30 mm wide, centred on 0).
  const double r = 0.00034;
  p.position.push_back(0.035);
  p.position.push_back(0.0);
  p.radius.push_back(r);
  const std::size_t thrown = p.size() - 1;
  sp::SpParams params = table1(0.0015);
  params.open_water_drag = true;
  sp::ExplicitModel model(params);
  model.initialise({p.radius, p.position});
  std::vector<double> x = p.position, d(x.size(), 0.0), v(x.size(), 0.0), f(x.size(), 0.0);
  model.step(0.0, 0.0, {x, v, d, {}}, f);  // the t = 0 exchange
  const std::vector<double> at_rest = f;
  // One step of 1e-7 s in which only the thrown grain moves, at (6, -3) m/s.
  const double dt = 1e-7, vx = 6.0, vy = -3.0;
  d[2 * thrown] = vx * dt;
  d[2 * thrown + 1] = vy * dt;
  x[2 * thrown] += d[2 * thrown];
  x[2 * thrown + 1] += d[2 * thrown + 1];
  model.step(dt, dt, {x, v, d, {}}, f);
  ASSERT_EQ(model.boundary()[thrown], sp::Boundary::drained);
  double ex = 0.0, ey = 0.0;
  sp::add_open_water_drag(r, vx, vy, params.water_density_kg_m3, params.viscosity_pa_s, ex, ey);
  // Alone, the pressure puts no force on it (p_hydro around it): the force is the drag, to the
  // displacement's rounding (x + d - x differs from d by ~1e-17 m in 6e-7 m).
  EXPECT_NEAR(f[2 * thrown], ex, std::abs(ex) * 1e-9);
  EXPECT_NEAR(f[2 * thrown + 1], ey, std::abs(ex) * 1e-9);
  EXPECT_NEAR(model.drag_power_w_per_m(), ex * vx + ey * vy, std::abs(ex * vx) * 1e-9);
  EXPECT_LT(model.drag_power_w_per_m(), 0.0);
  // Every grain of the packing is at rest: its force is the pressure's alone, as before.
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    EXPECT_EQ(f[2 * i], at_rest[2 * i]) << i;
    EXPECT_EQ(f[2 * i + 1], at_rest[2 * i + 1]) << i;
  }

  // The packing moving as one body at (6, -3) m/s: its drained surface grains feel the drag, its
  // interior grains (the pore water moves with them) do not.
  // One step of a model initialised on the packing, every grain displaced by (vx, vy) dt.
  const auto rigid_step = [&](sp::ExplicitModel& model, std::vector<double>& force) {
    model.initialise({p.radius, p.position});
    std::vector<double> y = p.position, dd(y.size(), 0.0);
    model.step(0.0, 0.0, {y, v, dd, {}}, force);
    for (std::size_t i = 0; i < p.size(); ++i) {
      dd[2 * i] = vx * dt;
      dd[2 * i + 1] = vy * dt;
      y[2 * i] += dd[2 * i];
      y[2 * i + 1] += dd[2 * i + 1];
    }
    model.step(dt, dt, {y, v, dd, {}}, force);
  };
  std::vector<double> g(x.size(), 0.0);
  {
    sp::ExplicitModel moving(params);
    rigid_step(moving, g);
    std::size_t drained = 0, interior = 0;
    double power = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      double dx = 0.0, dy = 0.0;
      sp::add_open_water_drag(p.radius[i], vx, vy, params.water_density_kg_m3,
                              params.viscosity_pa_s, dx, dy);
      if (moving.boundary()[i] == sp::Boundary::drained) {
        ++drained;
        power += dx * vx + dy * vy;
      } else {
        ++interior;
      }
    }
    EXPECT_GT(drained, 100u);
    EXPECT_GT(interior, 1000u);
    // Sum of the drained grains' drag power, in the same order: the same bits.
    EXPECT_EQ(moving.drag_power_w_per_m(), power);
  }
  // Off (the paper's model), the same rigid motion gives no power and the bare pressure force.
  sp::SpParams off = params;
  off.open_water_drag = false;
  sp::ExplicitModel paper(off);
  std::vector<double> h(x.size(), 0.0);
  rigid_step(paper, h);
  EXPECT_EQ(paper.drag_power_w_per_m(), 0.0);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    double dx = 0.0, dy = 0.0;
    if (paper.boundary()[i] == sp::Boundary::drained) {
      sp::add_open_water_drag(p.radius[i], vx, vy, params.water_density_kg_m3,
                              params.viscosity_pa_s, dx, dy);
    }
    // With the drag: the bare force plus the law's, on the drained grains only.
    EXPECT_NEAR(g[2 * i], h[2 * i] + dx, 1e-9 * (std::abs(h[2 * i]) + std::abs(dx) + 1e-6)) << i;
    differ += g[2 * i] != h[2 * i];
  }
  EXPECT_GT(differ, 100u);
}

}  // namespace
}  // namespace rockcut::fluid::test
