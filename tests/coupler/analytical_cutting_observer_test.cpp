// Which cuts get the analytical models (coupler/observers/run_observers.cpp): a cutting scene with
// a `rock` block, after the cutting summary whose forces its ratios read; no other scene.
#include <gtest/gtest.h>

#include <filesystem>

#include "observers/analytical_cutting.hpp"
#include "observers/cutting_summary.hpp"
#include "observers/run_observers.hpp"
#include "scene/scene_loader.hpp"

namespace rockcut::coupler {
namespace {

namespace fs = std::filesystem;

RunObservers observers_of(const rockcut::Scene& scene) {
  RunObservers observers;
  TimePlan plan;
  plan.dt_s = 1e-8;
  ObserverInputs inputs{"dem_module (test)", false, {}, {}, fs::path("/nonexistent")};
  register_observers(scene, plan, inputs, observers);
  return observers;
}

rockcut::Scene shipped(const std::string& name) {
  return scene::load_scene(fs::path(ROCKCUT_SOURCE_DIR) / "cases" / name, {}).scene;
}

TEST(AnalyticalCuttingObserver, OnlyACutWithARockHasIt) {
  rockcut::Scene cut = shipped("cutting/dry_reduced.pbtxt");
  ASSERT_TRUE(cut.has_rock());
  EXPECT_NE(observers_of(cut).find<AnalyticalCutting>(), nullptr);
  cut.clear_rock();
  EXPECT_EQ(observers_of(cut).find<AnalyticalCutting>(), nullptr);
  // A loading test takes the same rock file but has no tool: no models.
  const rockcut::Scene ucs = shipped("calibration/ucs.pbtxt");
  ASSERT_TRUE(ucs.has_rock());
  EXPECT_EQ(observers_of(ucs).find<AnalyticalCutting>(), nullptr);
}

TEST(AnalyticalCuttingObserver, RatiosReadTheCuttingSummarysForces) {
  const rockcut::Scene cut = shipped("cutting/dry_reduced.pbtxt");
  const AnalyticalCutting analytical(cut);
  Summary summary;
  summary.set("force_horizontal_mean_n_per_m", 51000.0);
  summary.set("force_horizontal_peak_n_per_m", 204000.0);
  analytical.write(summary);
  // Evans at the scene's 60 deg tool, 20 mm deep, BTS 2.55 MPa: 2 sigma_t d = 102 kN/m.
  EXPECT_DOUBLE_EQ(std::get<double>(*summary.get("analytical_evans_force_horizontal_n_per_m")), 102000.0);
  EXPECT_DOUBLE_EQ(std::get<double>(*summary.get("analytical_evans_ratio_mean")), 0.5);
  EXPECT_DOUBLE_EQ(std::get<double>(*summary.get("analytical_evans_ratio_peak")), 2.0);
  // A saturated cut at depth: the hyperbaric under-pressure is the cavitation bound
  // p_atm + rho_w g z - p_vapour of the scene's fluid.
  rockcut::Scene deep = shipped("cutting/saturated_reduced.pbtxt");
  deep.set_water_depth_m(1000.0);
  const AnalyticalCutting at_depth(deep);
  Summary s2;
  at_depth.write(s2);
  const rockcut::Fluid& f = deep.fluid();
  EXPECT_DOUBLE_EQ(std::get<double>(*s2.get("analytical_hyperbaric_under_pressure_pa")),
                   f.atmospheric_pressure_pa() + f.water_density_kg_m3() * f.gravity_m_s2() * 1000.0 -
                       f.cavitation_pressure_pa());
  EXPECT_GT(std::get<double>(*s2.get("analytical_hyperbaric_force_horizontal_n_per_m")),
            std::get<double>(*s2.get("analytical_merchant_force_horizontal_n_per_m")));
}

}  // namespace
}  // namespace rockcut::coupler
