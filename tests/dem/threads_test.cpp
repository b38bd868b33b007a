// OpenMP: two threads give the physics of one (to round-off: only the order of the force sums
// differs), and the same thread count reproduces a run bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>
#include <random>

#include "core/dem_system.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

// The pair laws the thread contracts must hold for: local damping alone (the paper's), and
// dashpots with rolling springs (each a templated variant of the pair loops).
struct Laws {
  double local_damping = 0.1;
  double damping_ratio = 0.0;
  double rolling_friction = 0.0;
};
const Laws kLocal{};
const Laws kDashpotsAndRolling{0.0, 0.1, 0.1};

DemSystem loaded_block(int threads, const Laws& laws = kLocal) {
  Particles p = test::hex_block(30, 20, 1e-3);
  std::mt19937_64 rng(3);
  for (double& v : p.velocity) v = 0.05 * ((rng() >> 11) * 0x1.0p-53 - 0.5);
  BondSet bonds = test::bond_all_touching(p, {1e10, 2.5e10, 2e3, 4e3});  // weak: bonds break
  DemSettings s;
  s.contact = {1e10, 2.5e10, 0.5, laws.damping_ratio, laws.rolling_friction};
  s.local_damping = laws.local_damping;
  s.threads = threads;
  WallSet walls;
  walls.add_body("press", {-0.001, 0.0, -0.001, 0.04}, false, 2.0, 0.0);  // pushes from the left
  return DemSystem(std::move(p), s, std::move(bonds), std::move(walls));
}

void run(DemSystem& s) {
  for (int k = 0; k < 1500; ++k) s.step(2e-8);
}

TEST(Threads, TwoAndThreeThreadsGiveTheSameRunAsOne) {
  // Each thread adds its pairs' forces on its own particles straight into the arrays and buffers
  // the rest; the buffers are read back only over each thread's window of foreign particles. A
  // window too narrow drops forces (and leaves them to pile up in the buffer); three threads give
  // the middle one foreign particles on both sides, and the press on the left edge makes thread
  // 0's window reach across every other thread's rows.
  for (const Laws& laws : {kLocal, kDashpotsAndRolling}) {
  DemSystem one = loaded_block(1, laws);
  run(one);
  ASSERT_GT(one.breaks().size(), 0u) << "the test should exercise bond breaks";
  for (int threads : {2, 3}) {
    DemSystem many = loaded_block(threads, laws);
    // The first evaluation, at the same positions: the forces agree to round-off of their sums.
    const DemSystem first = loaded_block(1, laws);
    for (std::size_t k = 0; k < first.particles().force.size(); ++k) {
      ASSERT_NEAR(first.particles().force[k], many.particles().force[k],
                  1e-12 * (1.0 + std::abs(first.particles().force[k])))
          << k << ", " << threads << " threads";
    }
    run(many);
    EXPECT_EQ(one.breaks().size(), many.breaks().size()) << threads << " threads";
    // Summation order differs between thread counts: differences start at round-off (1e-16
    // relative) and grow with the number of steps; 1e-9 m is far below a disc's radius (1e-3 m)
    // and far above round-off growth over 1500 steps.
    for (std::size_t k = 0; k < one.particles().position.size(); ++k) {
      ASSERT_NEAR(one.particles().position[k], many.particles().position[k], 1e-9)
          << k << ", " << threads << " threads";
    }
  }
  }
}

TEST(Threads, SameThreadCountReproducesBitForBit) {
  for (const Laws& laws : {kLocal, kDashpotsAndRolling}) {
    DemSystem a = loaded_block(2, laws), b = loaded_block(2, laws);
    run(a);
    run(b);
    const auto& pa = a.particles().position;
    const auto& pb = b.particles().position;
    EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(double)), 0);
    EXPECT_EQ(a.walls().bodies()[0].force_x, b.walls().bodies()[0].force_x);
  }
}

TEST(Threads, OneRegionStepEqualsTheSplitStepBitForBit) {
  // step() runs a whole step in one parallel region (DemSystem::full_step); the coupled run's
  // split step (begin_step, internal forces, finish_step) runs the same passes on the same
  // particle and pair shares in three regions. The motion must agree to the bit for either
  // thread count, through bond breaks and neighbour rebuilds.
  for (const Laws& laws : {kLocal, kDashpotsAndRolling})
  for (int threads : {1, 2}) {
    DemSystem full = loaded_block(threads, laws), split = loaded_block(threads, laws);
    const std::vector<double> none(full.particles().position.size(), 0.0);
    for (int k = 0; k < 1500; ++k) {
      full.step(2e-8);
      split.begin_step(2e-8);
      split.compute_internal_forces();
      split.finish_step(2e-8, none);
    }
    ASSERT_GT(full.breaks().size(), 0u) << "the test should exercise bond breaks";
    ASSERT_GT(full.neighbour_rebuilds(), 1u) << "the test should exercise a rebuild";
    EXPECT_EQ(full.breaks().size(), split.breaks().size());
    EXPECT_EQ(full.neighbour_rebuilds(), split.neighbour_rebuilds());
    const auto& a = full.particles();
    const auto& b = split.particles();
    EXPECT_EQ(std::memcmp(a.position.data(), b.position.data(), a.position.size() * 8), 0)
        << threads << " threads";
    EXPECT_EQ(std::memcmp(a.velocity.data(), b.velocity.data(), a.velocity.size() * 8), 0)
        << threads << " threads";
    // The ledger's terms are summed per thread and pass in a different grouping: round-off.
    EXPECT_NEAR(full.ledger().damping_j, split.ledger().damping_j,
                1e-12 * std::abs(split.ledger().damping_j));
    EXPECT_NEAR(full.ledger().boundary_work_j, split.ledger().boundary_work_j,
                1e-12 * std::abs(split.ledger().boundary_work_j));
    EXPECT_NEAR(full.ledger().viscous_damping_j, split.ledger().viscous_damping_j,
                1e-12 * std::abs(split.ledger().viscous_damping_j));
  }
}

TEST(Threads, ANeighbourRebuildSharedOutListsThePairsInTheSerialOrder) {
  // The contact search runs on every thread of the team, each over its share of the particles,
  // and the shares are joined in thread order: the list (and so the order of the force sums)
  // must be the one rebuild() gives on one thread, at any thread count.
  Particles p = test::hex_block(30, 20, 1e-3);
  std::mt19937_64 rng(5);
  for (double& x : p.position) x += 2e-5 * ((rng() >> 11) * 0x1.0p-53 - 0.5);
  BondSet bonds = test::bond_all_touching(p, {1e10, 2.5e10, 2e3, 4e3});
  bonds.refresh_partners(p.size());
  const double skin_m = 2e-4;
  CellGrid grid;
  ContactList serial;
  serial.rebuild(p, bonds, skin_m, grid);
  ASSERT_GT(serial.size(), 100u) << "the test needs unbonded pairs within the skin";
  for (int threads : {2, 3, 7}) {
    ContactList shared;
    CellGrid g;
    shared.begin_rebuild(p, skin_m, g, threads);
    for (int t = threads - 1; t >= 0; --t) shared.search(p, bonds, skin_m, g, t, threads);
    shared.size_join();
    for (int t = threads - 1; t >= 0; --t) shared.join(t);
    ASSERT_EQ(shared.size(), serial.size()) << threads;
    for (std::size_t k = 0; k < serial.size(); ++k) {
      ASSERT_EQ(shared.first(k), serial.first(k)) << threads << " threads, pair " << k;
      ASSERT_EQ(shared.second(k), serial.second(k)) << threads << " threads, pair " << k;
    }
  }
  // And a system stepping on three threads rebuilds its lists as it goes.
  DemSystem many = loaded_block(3);
  run(many);
  EXPECT_GT(many.neighbour_rebuilds(), 1u);
}

}  // namespace
}  // namespace rockcut::dem
