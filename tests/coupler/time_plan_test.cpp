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

}  // namespace
}  // namespace rockcut::coupler
