// The time plan refuses a run that would make no step: an end time shorter than one time step
// (with time.ignore_limits a dt far above the end time "completed" with 0 steps, exit 0); the
// pore fluid's stiffness limit that binds follows the scene's coupling.
#include <gtest/gtest.h>

#include "run/time_plan.hpp"

namespace rockcut::coupler {
namespace {

TEST(TimePlan, ARunOfNoStepIsRefused) {
  rockcut::Scene scene;
  scene.mutable_time()->set_end_time_s(1e-12);
  scene.mutable_time()->set_dt_s(1.0);
  scene.mutable_time()->set_ignore_limits(true);
  const std::vector<Limit> dem = {{"dem_module", "dem_springs", 1e-6, "", false, "", {}}};
  try {
    plan_time(scene, dem, {}, false);
    ADD_FAILURE() << "a plan of no step was made";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("less than one step"), std::string::npos) << e.what();
  }
  // One step's worth is a run.
  scene.mutable_time()->set_end_time_s(1.0);
  EXPECT_EQ(plan_time(scene, dem, {}, false).total_steps, 1u);
}

// The DEM extrapolates the fluid's force only where the scene asks for it and there are steps
// between exchanges (N > 1); a scene's N above the held limit is told of the extrapolated force.
TEST(TimePlan, TheForceIsExtrapolatedOnlyBetweenExchanges) {
  rockcut::Scene scene;
  scene.mutable_time()->set_end_time_s(1e-3);
  const std::vector<Limit> dem = {{"dem_module", "dem_springs", 1e-6, "", false, "", {}}};
  const Limit held{"fluid_module", "pore_fluid_stiffness", 1e-6, "", true,
                   "use coupling.fluid_force \"extrapolated\"", wire::LIMIT_KIND_PORE_FLUID_STIFFNESS};
  // dt = 0.2 us: the held limit allows N <= 5, a quarter of which is N = 1.
  EXPECT_FALSE(plan_time(scene, dem, {held}, true).extrapolate_fluid_force);
  scene.mutable_coupling()->set_fluid_force("extrapolated");
  const TimePlan quarter = plan_time(scene, dem, {held}, true);
  EXPECT_EQ(quarter.coupling_interval, 1u);
  EXPECT_FALSE(quarter.extrapolate_fluid_force);
  scene.mutable_coupling()->set_interval(4);
  EXPECT_TRUE(plan_time(scene, dem, {held}, true).extrapolate_fluid_force);

  scene.mutable_coupling()->set_fluid_force("held");
  scene.mutable_coupling()->set_interval(6);
  try {
    plan_time(scene, dem, {held}, true);
    ADD_FAILURE() << "N = 6 above the limit's 5 was planned";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("use coupling.interval <= 5, or use coupling.fluid_force "
                                         "\"extrapolated\""),
              std::string::npos)
        << e.what();
  }
}

// Of the fluid's two stiffness limits the one for the scene's fluid_force binds, and the lag's
// energy taken out moves the extrapolated one by kLagPassivityLimitFactor, not the held one. With
// the paper-scale dynamic cut's own limits (dt 3.974e-8 s, the extrapolated limit 1.978e-7 s,
// its start-up report) that is N = 4 without the correction and N = 8 with it.
TEST(TimePlan, TheLagsCorrectionMovesOnlyTheExtrapolatedForcesLimit) {
  const Limit held{"fluid_module", "pore_fluid_stiffness", 7.96e-8, "", true, "",
                   wire::LIMIT_KIND_PORE_FLUID_STIFFNESS};
  const Limit extrapolated{"fluid_module", "pore_fluid_stiffness_extrapolated", 1.978e-7, "",
                           true, "", wire::LIMIT_KIND_PORE_FLUID_STIFFNESS_EXTRAPOLATED};
  const Limit diffusion{"fluid_module", "explicit_diffusion", 5.6e-6, "", false, "",
                        wire::LIMIT_KIND_UNSPECIFIED};
  rockcut::Scene scene;
  scene.mutable_time()->set_end_time_s(1e-4);
  scene.mutable_time()->set_dt_s(3.974e-8);
  scene.mutable_coupling()->set_interval_fraction(1.0);
  const std::vector<Limit> dem = {{"dem_module", "dem_springs", 1.987e-7, "", false, "", {}}};
  auto bound = [&](const std::vector<Limit>& limits) {
    return applicable_fluid_limits(scene, limits);
  };
  auto interval = [&] {
    return plan_time(scene, dem, bound({held, extrapolated, diffusion}), true).coupling_interval;
  };

  // Held (the schema's default): the held limit and the diffusion limit, with or without the
  // correction, which was not measured with the held force.
  for (const char* correction : {"none", "passivity"}) {
    scene.mutable_coupling()->set_lag_correction(correction);
    const std::vector<Limit> limits = bound({held, extrapolated, diffusion});
    ASSERT_EQ(limits.size(), 2u) << correction;
    EXPECT_EQ(limits[0].kind, wire::LIMIT_KIND_PORE_FLUID_STIFFNESS);
    EXPECT_EQ(limits[0].dt_max_s, held.dt_max_s) << correction;
    EXPECT_EQ(limits[1].dt_max_s, diffusion.dt_max_s);
    EXPECT_EQ(interval(), 2u) << correction;  // 7.96e-8 / 3.974e-8
  }

  scene.mutable_coupling()->set_fluid_force("extrapolated");
  scene.mutable_coupling()->set_lag_correction("none");
  std::vector<Limit> limits = bound({held, extrapolated, diffusion});
  ASSERT_EQ(limits.size(), 2u);
  EXPECT_EQ(limits[0].kind, wire::LIMIT_KIND_PORE_FLUID_STIFFNESS_EXTRAPOLATED);
  EXPECT_EQ(limits[0].dt_max_s, extrapolated.dt_max_s);
  EXPECT_EQ(interval(), 4u);  // 1.978e-7 / 3.974e-8 = 4.98

  scene.mutable_coupling()->set_lag_correction("passivity");
  limits = bound({held, extrapolated, diffusion});
  ASSERT_EQ(limits.size(), 2u);
  EXPECT_DOUBLE_EQ(limits[0].dt_max_s, extrapolated.dt_max_s * kLagPassivityLimitFactor);
  EXPECT_NE(limits[0].detail.find("lag_correction \"passivity\""), std::string::npos)
      << limits[0].detail;
  EXPECT_EQ(limits[1].dt_max_s, diffusion.dt_max_s);  // the other limits stay
  const TimePlan plan = plan_time(scene, dem, limits, true);
  EXPECT_EQ(plan.coupling_interval, 8u);  // 3.264e-7 / 3.974e-8 = 8.21
  EXPECT_TRUE(plan.lag_passivity);
  EXPECT_TRUE(plan.extrapolate_fluid_force);
  EXPECT_FALSE(plan.fluid_self_stiffness);  // the schema's default, "none"

  // Each grain's own fluid stiffness moves no limit (its effect on the lag is measured, not
  // derived: docs/model.md) and is applied only where there is a lag, N > 1.
  scene.mutable_coupling()->set_fluid_stiffness("self");
  const TimePlan stiffened = plan_time(scene, dem, bound({held, extrapolated, diffusion}), true);
  EXPECT_EQ(stiffened.coupling_interval, 8u);
  EXPECT_TRUE(stiffened.fluid_self_stiffness);
  scene.mutable_coupling()->set_interval(1);
  EXPECT_FALSE(plan_time(scene, dem, bound({held, extrapolated, diffusion}), true)
                   .fluid_self_stiffness);
}

}  // namespace
}  // namespace rockcut::coupler
