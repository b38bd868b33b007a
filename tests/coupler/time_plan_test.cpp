// The time plan refuses a run that would make no step: an end time shorter than one time step
// (with time.ignore_limits a dt far above the end time "completed" with 0 steps, exit 0).
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

}  // namespace
}  // namespace rockcut::coupler
