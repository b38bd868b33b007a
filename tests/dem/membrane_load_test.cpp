// The membrane of a biaxial test (core/membrane_load.hpp): the outermost disc of each band of each
// side carries the band's share, so each side's line load is sigma_c H, inward.
#include <gtest/gtest.h>

#include <cmath>

#include "core/membrane_load.hpp"
#include "core/specimen_generator.hpp"

namespace rockcut::dem {
namespace {

TEST(MembraneLoad, EachSideCarriesSigmaTimesHeightOnItsOutermostDiscs) {
  // Three columns of discs 1 mm apart, ten rows: the left column is the outermost on the left, the
  // right column on the right; the middle column is never loaded. Radius 0.5 mm: bands of 1 mm.
  Particles p;
  for (int row = 0; row < 10; ++row) {
    for (int col = 0; col < 3; ++col) p.add(0.001 * col, 0.001 * row, 0.0005, 2800.0);
  }
  const double stress = 2e6;
  const MembraneLoad m = membrane_load(p, stress);
  EXPECT_DOUBLE_EQ(m.height_m, 0.010);
  ASSERT_EQ(m.particles.size(), 20u);
  double left = 0.0, right = 0.0;
  for (std::size_t k = 0; k < m.particles.size(); ++k) {
    const double x = p.position[2 * m.particles[k]];
    if (m.force_x_n_per_m[k] > 0) {
      EXPECT_DOUBLE_EQ(x, 0.0);
      left += m.force_x_n_per_m[k];
    } else {
      EXPECT_DOUBLE_EQ(x, 0.002);
      right -= m.force_x_n_per_m[k];
    }
  }
  EXPECT_NEAR(left, stress * 0.010, 1e-9);
  EXPECT_NEAR(right, stress * 0.010, 1e-9);
}

TEST(MembraneLoad, ARandomSpecimensBandsEachHaveTheirOutermostDisc) {
  // A random packing: every band of 2 r_max holds discs, so each side has one loaded disc per band
  // and the line load is sigma_c H.
  PackingSpec spec;
  spec.region.center_x_m = 0.005;
  spec.region.center_y_m = 0.01;
  spec.region.width_m = 0.01;
  spec.region.height_m = 0.02;
  spec.radius_min_m = 0.0002;
  spec.radius_max_m = 0.0004;
  spec.seed = 3;
  const Packing packing = generate_packing(spec);
  Particles p;
  for (std::size_t i = 0; i < packing.size(); ++i) {
    p.add(packing.x_m[i], packing.y_m[i], packing.radius_m[i], 2800.0);
  }
  const MembraneLoad m = membrane_load(p, 1e6);
  double left = 0.0;
  for (double f : m.force_x_n_per_m) left += f > 0 ? f : 0.0;
  EXPECT_NEAR(left / (1e6 * m.height_m), 1.0, 1e-12);
  const auto bands = static_cast<std::size_t>(std::ceil(m.height_m / 0.0008));
  EXPECT_EQ(m.particles.size(), 2 * bands);
}

}  // namespace
}  // namespace rockcut::dem
