// A run builds the observers its scene asks for and no others (coupler/observers/run_observers.cpp).
#include <gtest/gtest.h>

#include <filesystem>

#include "observers/calibration_summary.hpp"
#include "observers/cutting_summary.hpp"
#include "observers/energy_budget.hpp"
#include "observers/expected_error.hpp"
#include "observers/peclet.hpp"
#include "observers/pressure_nodes.hpp"
#include "observers/run_observers.hpp"
#include "scene/scene_loader.hpp"

namespace rockcut::coupler {
namespace {

namespace fs = std::filesystem;

struct Built {
  scene::LoadedScene loaded;
  RunObservers observers;
  VerificationCheck* verification = nullptr;
};

// The observers of the shipped case `name`; `fluid_has_pressure` as the started fluid would say.
std::unique_ptr<Built> build(const std::string& name, bool fluid_has_pressure) {
  auto b = std::make_unique<Built>();
  b->loaded = scene::load_scene(fs::path(ROCKCUT_SOURCE_DIR) / "cases" / name, {});
  TimePlan plan;
  plan.dt_s = 1e-8;
  ObserverInputs inputs{"dem_module (test)", fluid_has_pressure, {}, {}, fs::path("/nonexistent")};
  register_observers(b->loaded.scene, plan, inputs, b->observers);
  b->verification = b->observers.find<VerificationCheck>();
  return b;
}

TEST(RunObservers, ADryCutHasACuttingSummaryAndNothingOfTheFluid) {
  const auto b = build("cutting/dry_reduced.pbtxt", false);
  EXPECT_NE(b->observers.find<CuttingSummary>(), nullptr);
  EXPECT_NE(b->observers.find<EnergyReport>(), nullptr);
  EXPECT_EQ(b->observers.find<PressureNodeProbes>(), nullptr);
  EXPECT_EQ(b->observers.find<PecletReport>(), nullptr);
  EXPECT_EQ(b->observers.find<CalibrationSummary>(), nullptr);
  EXPECT_EQ(b->verification, nullptr);
}

TEST(RunObservers, ASaturatedCutHasPressureNodesOnlyWhenTheFluidHasAPressure) {
  const auto with = build("cutting/saturated_reduced.pbtxt", true);
  EXPECT_NE(with->observers.find<CuttingSummary>(), nullptr);
  EXPECT_NE(with->observers.find<PressureNodeProbes>(), nullptr);
  EXPECT_NE(with->observers.find<PecletReport>(), nullptr);
  EXPECT_EQ(with->observers.find<CalibrationSummary>(), nullptr);
  // A fluid model without a pressure (prescribed_gradient, a third party's): no probes to place.
  const auto without = build("cutting/saturated_reduced.pbtxt", false);
  EXPECT_EQ(without->observers.find<PressureNodeProbes>(), nullptr);
  EXPECT_NE(without->observers.find<CuttingSummary>(), nullptr);
}

TEST(RunObservers, ALoadingTestHasACalibrationFitAndNoCuttingSummary) {
  const auto b = build("calibration/brazilian.pbtxt", false);
  EXPECT_NE(b->observers.find<CalibrationSummary>(), nullptr);
  EXPECT_EQ(b->observers.find<CuttingSummary>(), nullptr);
  EXPECT_EQ(b->observers.find<PressureNodeProbes>(), nullptr);
}

TEST(RunObservers, AVerificationSceneHasItsCheckAskingForItsFields) {
  const auto b = build("verification/terzaghi.pbtxt", true);
  ASSERT_NE(b->verification, nullptr);
  EXPECT_EQ(b->verification->fields(), std::vector<std::string>{"pressure"});
  EXPECT_EQ(b->observers.find<CuttingSummary>(), nullptr);
  EXPECT_EQ(b->observers.find<CalibrationSummary>(), nullptr);
}

}  // namespace
}  // namespace rockcut::coupler
