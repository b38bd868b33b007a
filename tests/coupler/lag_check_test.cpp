// The lag check: per 5 mm of the tool's travel, where the coupling lag's correction took more than
// the pore fluid dissipated. Ledgers made up so that each window's verdict is known.
#include <gtest/gtest.h>

#include <variant>
#include <vector>

#include "observers/lag_check.hpp"

namespace rockcut::coupler {
namespace {

// One time-series row: the ledger's cumulative terms [J/m] at a travel [m].
RunClock ledger_row(double travel_m, double correction_j, double fluid_work_j, double tool_work_j) {
  RunClock clock;
  clock.scalars = {{"boundary_work_j", tool_work_j},
                   {"external_work_j", fluid_work_j},
                   {"lag_correction_j", correction_j},
                   {"tool_travel_m", travel_m}};
  return clock;
}

std::int64_t summary_count(const Summary& s, const char* key) {
  return std::get<std::int64_t>(*s.get(key));
}

TEST(LagCheck, AWindowIsResolvedWhereTheCorrectionTookMoreThanTheFluidDissipated) {
  LagCheck check;
  // Rows every millimetre over 20 mm: four windows of 5 mm. Per millimetre the tool does 10
  // J/m; the fluid dissipates 4 J/m and the correction takes 0.1 J/m, except from 10 to 15 mm,
  // where the fluid puts 1 J/m in and the correction takes 3.
  double correction = 0.0, fluid = 0.0, tool = 0.0;
  check.row(ledger_row(0.0, correction, fluid, tool));
  for (int mm = 1; mm <= 20; ++mm) {
    const bool lagged = mm > 10 && mm <= 15;
    correction += lagged ? 3.0 : 0.1;
    fluid += lagged ? 1.0 : -4.0;  // the fluid's work: negative where it dissipates
    tool += 10.0;
    check.row(ledger_row(1e-3 * mm, correction, fluid, tool));
  }
  EXPECT_EQ(check.windows(), 4u);
  EXPECT_EQ(check.resolved_windows(), 1u);
  EXPECT_NEAR(check.first_resolved_m(), 0.010, 1e-12);
  Summary summary;
  check.finish(RunClock{}, summary, true);
  EXPECT_EQ(summary_count(summary, "lag_windows"), 4);
  EXPECT_EQ(summary_count(summary, "lag_resolved_windows"), 1);
}

TEST(LagCheck, AToolInAirAndARowWithoutTheCorrectionAreNotCounted) {
  LagCheck check;
  // 10 mm in air before the rock: round-off in both works, the correction above the fluid's but
  // below 1 % of the tool's work (which is round-off too).
  check.row(ledger_row(0.0, 0.0, 0.0, 0.0));
  check.row(ledger_row(0.005, 1e-12, 1e-13, 1e-9));
  check.row(ledger_row(0.010, 2e-12, 2e-13, 2e-9));
  EXPECT_EQ(check.windows(), 2u);
  // 5 mm of cut (200 J/m, the fluid dissipating 80), then 5 mm in air after the chip: the
  // fragments put 0.1 J/m into the fluid and the correction takes 0.5, 0.2 % of the tool's work.
  check.row(ledger_row(0.015, 1.0, -80.0, 200.0));
  check.row(ledger_row(0.020, 1.5, -79.9, 201.0));
  EXPECT_EQ(check.windows(), 4u);
  EXPECT_EQ(check.resolved_windows(), 0u);
  EXPECT_LT(check.first_resolved_m(), 0.0);
  // A row without the correction's ledger (a DEM not asked for it) is skipped.
  RunClock without = ledger_row(0.025, 0.0, 0.0, 0.0);
  std::erase_if(without.scalars, [](const auto& kv) { return kv.first == "lag_correction_j"; });
  check.row(without);
  EXPECT_EQ(check.windows(), 4u);
}

TEST(LagCheck, ItsStateSurvivesACheckpoint) {
  // A run resumed half-way through a window counts what the whole run counts.
  auto feed = [](LagCheck& c, int from_mm, int to_mm) {
    for (int mm = from_mm; mm <= to_mm; ++mm) {
      const double lagged = mm > 5 ? 1.0 : 0.0;
      c.row(ledger_row(1e-3 * mm, 0.1 * mm + 5.0 * lagged * (mm - 5), -4.0 * mm, 10.0 * mm));
    }
  };
  LagCheck whole;
  feed(whole, 0, 12);
  LagCheck first;
  feed(first, 0, 7);
  state::StateArchive a;
  first.save_state(a);
  LagCheck resumed;
  resumed.load_state(a);
  feed(resumed, 8, 12);
  EXPECT_EQ(resumed.windows(), whole.windows());
  EXPECT_EQ(resumed.resolved_windows(), whole.resolved_windows());
  EXPECT_EQ(resumed.first_resolved_m(), whole.first_resolved_m());
  EXPECT_EQ(whole.windows(), 2u);
  EXPECT_EQ(whole.resolved_windows(), 1u);
  // A checkpoint written without the check starts it afresh instead of failing.
  LagCheck fresh;
  fresh.load_state(state::StateArchive{});
  EXPECT_EQ(fresh.windows(), 0u);
}

}  // namespace
}  // namespace rockcut::coupler
