// A refused state changes nothing: DemSystem::load_state checks every member's size and index
// before any of them replaces the running system's, so a step after a refused LoadState runs on
// the system as it was, bit for bit (no half-loaded list read out of bounds).
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <random>

#include "core/dem_system.hpp"
#include "dem/dem_test_support.hpp"

namespace rockcut::dem {
namespace {

DemSystem pressed_block() {
  // Densities that differ from disc to disc, so that each bond's pair has its own effective mass.
  const Particles hex = test::hex_block(12, 8, 1e-3);
  Particles p;
  for (std::size_t i = 0; i < hex.size(); ++i) {
    p.add(hex.position[2 * i], hex.position[2 * i + 1], hex.radius[i], 2000.0 + 150.0 * (i % 7));
  }
  std::mt19937_64 rng(5);
  for (double& v : p.velocity) v = 0.05 * ((rng() >> 11) * 0x1.0p-53 - 0.5);
  BondSet bonds = test::bond_all_touching(p, {1e10, 2.5e10, 2e3, 4e3});
  DemSettings s;
  s.contact = {1e10, 2.5e10, 0.5, 0.1, 0.1};
  WallSet walls;
  walls.add_body("press", {-0.001, 0.0, -0.001, 0.02}, false, 2.0, 0.0);
  return DemSystem(std::move(p), s, std::move(bonds), std::move(walls));
}

TEST(LoadState, ARefusedStateLeavesTheSystemAsItWas) {
  // Each corruption passes the earlier members' checks and fails a later one, after the
  // particle arrays and some lists would already have been assigned.
  const std::vector<std::pair<const char*, std::function<void(state::StateArchive&, std::size_t)>>>
      corruptions = {
          {"a bond index past the particles",
           [](state::StateArchive& a, std::size_t n) {
             auto v = std::vector<double>(a.values("bond_i").begin(), a.values("bond_i").end());
             v.back() = static_cast<double>(n + 7);
             a.put("bond_i", std::move(v));
           }},
          {"a contact list one entry short",
           [](state::StateArchive& a, std::size_t) {
             auto v = std::vector<double>(a.values("contact_j").begin(), a.values("contact_j").end());
             v.pop_back();
             a.put("contact_j", std::move(v));
           }},
          {"a wall pair naming a missing segment",
           [](state::StateArchive& a, std::size_t) {
             auto v = std::vector<double>(a.values("wall_pair_segment").begin(),
                                          a.values("wall_pair_segment").end());
             ASSERT_FALSE(v.empty());
             v.front() = 99.0;
             a.put("wall_pair_segment", std::move(v));
           }},
          {"a ledger of the wrong length",
           [](state::StateArchive& a, std::size_t) { a.put("ledger_j", std::vector<double>{1.0}); }},
      };
  for (const auto& [what, corrupt] : corruptions) {
    DemSystem live = pressed_block(), reference = pressed_block();
    for (int k = 0; k < 300; ++k) {
      live.step(2e-8);
      reference.step(2e-8);
    }
    DemSystem donor = pressed_block();
    for (int k = 0; k < 500; ++k) donor.step(2e-8);  // another state, lists of other lengths
    state::StateArchive archive;
    donor.save_state(archive);
    corrupt(archive, donor.particles().size());
    EXPECT_THROW(live.load_state(archive), state::StateError) << what;
    for (int k = 0; k < 300; ++k) {
      live.step(2e-8);
      reference.step(2e-8);
    }
    const auto& a = live.particles().position;
    const auto& b = reference.particles().position;
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << what;
    EXPECT_EQ(live.bonds().size(), reference.bonds().size()) << what;
    EXPECT_EQ(live.ledger().boundary_work_j, reference.ledger().boundary_work_j) << what;
  }
}

TEST(LoadState, AGoodStateStillLoads) {
  // The donor has lost bonds before it is saved, so the loaded list is not the one `live` was
  // built with, and its discs differ in mass: each loaded bond's springs and dashpots must act on
  // the pair the archive names.
  DemSystem donor = pressed_block(), live = pressed_block();
  for (int k = 0; k < 500; ++k) donor.step(2e-8);
  ASSERT_LT(donor.bonds().size(), live.bonds().size()) << "the test should load a broken list";
  state::StateArchive archive;
  donor.save_state(archive);
  live.load_state(archive);
  for (int k = 0; k < 200; ++k) {
    donor.step(2e-8);
    live.step(2e-8);
  }
  const auto& a = live.particles().position;
  const auto& b = donor.particles().position;
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
}

}  // namespace
}  // namespace rockcut::dem
