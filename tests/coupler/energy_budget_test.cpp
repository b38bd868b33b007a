// The energy budget printed at the end of a run and written to summary.json: the DEM's ledger as
// shares of what came in. Ledgers made up so that every share is known exactly.
#include <gtest/gtest.h>

#include "observers/energy_budget.hpp"

namespace rockcut::coupler {
namespace {

std::vector<std::pair<std::string, double>> ledger(double boundary, double external,
                                                   double damping, double kinetic,
                                                   double imbalance = 0.0) {
  return {{"boundary_work_j", boundary}, {"external_work_j", external}, {"gravity_work_j", 0.0},
          {"damping_j", damping},        {"friction_j", 15.0},          {"broken_bond_j", 3.0},
          {"kinetic_energy_j", kinetic}, {"strain_energy_j", 1.0},
          {"energy_imbalance_j", imbalance}, {"bonds", 7.0}};
}

TEST(EnergyBudget, ACutsToolWorkSplitsIntoItsSinksAndTheFluidIsOneOfThem) {
  // Tool 100 J/m in; damping 70, friction 15, the fluid takes 10, bonds 3, kinetic + strain 2:
  // the initial energy is 0 and every sink's share is its joules in per cent.
  const auto b = energy_budget(ledger(100.0, -10.0, 70.0, 1.0));
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->initial_j(), 0.0);
  // Round-off of the ledger's sums is not reported as initial energy.
  const auto rounded = energy_budget(ledger(100.0, -10.0, 70.0, 1.0, 1e-12));
  ASSERT_TRUE(rounded.has_value());
  EXPECT_EQ(rounded->initial_j(), 0.0);
  EXPECT_EQ(describe(*rounded, "pore fluid").rfind("in: walls and tool 100 J/m;", 0), 0u);
  EXPECT_DOUBLE_EQ(b->input_j(), 100.0);
  // summary.json's terms: the ledger's own names and values, the imbalance left out.
  const auto terms = b->terms();
  ASSERT_EQ(terms.size(), 10u);
  EXPECT_STREQ(terms[3].first, "damping_j");
  EXPECT_EQ(terms[3].second, 70.0);
  EXPECT_STREQ(terms[1].first, "external_work_j");
  EXPECT_EQ(terms[1].second, -10.0);
  EXPECT_EQ(describe(*b, "pore fluid"),
            "in: walls and tool 100 J/m; out: local damping 70.0 %, friction 15.0 %, pore fluid "
            "10.0 %, broken bonds 3.0 %, kinetic + strain 2.0 %");
}

TEST(EnergyBudget, InitialEnergyAndAGivingExternalForceCountAsInput) {
  // Held 70 + 15 + 3 + 11 + 1 = 100 with 20 of work by the tool and 30 by the external force:
  // the remaining 50 was there at the start (e.g. overlaps' strain energy). The imbalance of 0.5
  // counts as given too (given = held + imbalance).
  const auto b = energy_budget(ledger(20.0, 30.0, 70.0, 11.0, 0.5));
  ASSERT_TRUE(b.has_value());
  EXPECT_NEAR(b->initial_j(), 50.5, 1e-12);
  EXPECT_NEAR(b->input_j(), 100.5, 1e-12);
  const std::string line = describe(*b, "external force");
  EXPECT_NE(line.find("in: initial 50.5 J/m, walls and tool 20 J/m, external force 30 J/m"),
            std::string::npos) << line;
  EXPECT_NE(line.find("local damping 69.7 %"), std::string::npos) << line;  // 70 / 100.5
  EXPECT_EQ(line.find("external force 0"), std::string::npos) << line;      // not a sink
}

TEST(EnergyBudget, DashpotsAndRollingResistanceAreSinksOfTheirOwn) {
  // Tool 100 J/m in; dashpots 12, rolling 5, friction 15, bonds 3, kinetic + strain 2, and the
  // fluid 63: with no local damping its share is left out, the dashpots' named instead, with
  // the bonds' part of them (7 of the 12) beside it, not added again.
  auto scalars = ledger(100.0, -63.0, 0.0, 1.0);
  scalars.push_back({"viscous_damping_j", 12.0});
  scalars.push_back({"viscous_damping_bonds_j", 7.0});
  scalars.push_back({"rolling_j", 5.0});
  const auto b = energy_budget(scalars);
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->initial_j(), 0.0);
  EXPECT_EQ(describe(*b, "pore fluid"),
            "in: walls and tool 100 J/m; out: viscous damping 12.0 % (bonds 7.0 %), friction 15.0 %, "
            "rolling resistance 5.0 %, pore fluid 63.0 %, broken bonds 3.0 %, kinetic + strain "
            "2.0 %");
  bool has_bonds_part = false;
  for (const auto& [key, value] : b->terms()) {
    if (std::string(key) == "viscous_damping_bonds_j") has_bonds_part = value == 7.0;
  }
  EXPECT_TRUE(has_bonds_part);
}

TEST(EnergyBudget, NoneWithoutTheLedgerAndNothingWhenNothingCameIn) {
  EXPECT_FALSE(energy_budget({{"kinetic_energy_j", 1.0}}).has_value());  // a ledger-less report
  // Held 15 + 3 + 1 = 19 against an imbalance of -19: given = held + imbalance = 0.
  const auto b = energy_budget(ledger(0.0, 0.0, 0.0, 0.0, -19.0));
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(describe(*b, "pore fluid"), "nothing came in");
}

}  // namespace
}  // namespace rockcut::coupler
