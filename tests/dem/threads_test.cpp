// OpenMP: two threads give the physics of one (to round-off: only the order of the force sums
// differs), and the same thread count reproduces a run bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/dem_system.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

DemSystem loaded_block(int threads) {
  Particles p = test::hex_block(30, 20, 1e-3);
  std::mt19937_64 rng(3);
  for (double& v : p.velocity) v = 0.05 * ((rng() >> 11) * 0x1.0p-53 - 0.5);
  BondSet bonds = test::bond_all_touching(p, {1e10, 2.5e10, 2e3, 4e3});  // weak: bonds break
  DemSettings s;
  s.contact = {1e10, 2.5e10, 0.5};
  s.local_damping = 0.1;
  s.threads = threads;
  WallSet walls;
  walls.add_body("press", {-0.001, 0.0, -0.001, 0.04}, false, 2.0, 0.0);  // pushes from the left
  return DemSystem(std::move(p), s, std::move(bonds), std::move(walls));
}

void run(DemSystem& s) {
  for (int k = 0; k < 1500; ++k) s.step(2e-8);
}

TEST(Threads, TwoThreadsGiveTheSameRunAsOne) {
  DemSystem one = loaded_block(1), two = loaded_block(2);
  run(one);
  run(two);
  ASSERT_GT(one.breaks().size(), 0u) << "the test should exercise bond breaks";
  EXPECT_EQ(one.breaks().size(), two.breaks().size());
  // Summation order differs between thread counts: differences start at round-off (1e-16
  // relative) and grow with the number of steps; 1e-9 m is far below a disc's radius (1e-3 m)
  // and far above round-off growth over 1500 steps.
  for (std::size_t k = 0; k < one.particles().position.size(); ++k) {
    ASSERT_NEAR(one.particles().position[k], two.particles().position[k], 1e-9) << k;
  }
}

TEST(Threads, SameThreadCountReproducesBitForBit) {
  DemSystem a = loaded_block(2), b = loaded_block(2);
  run(a);
  run(b);
  const auto& pa = a.particles().position;
  const auto& pb = b.particles().position;
  EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(double)), 0);
  EXPECT_EQ(a.walls().bodies()[0].force_x, b.walls().bodies()[0].force_x);
}

}  // namespace
}  // namespace rockcut::dem
