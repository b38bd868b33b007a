// The cutting summary's figures of the steady part, from samples whose values are worked by hand:
// the means over all samples and over the samples in which the tool touched rock, the peak, the
// contact fraction, the specific energy; samples before the steady part are left out.
#include <gtest/gtest.h>

#include <filesystem>
#include <variant>

#include "observers/cutting_summary.hpp"
#include "scene/scene_loader.hpp"

namespace rockcut::coupler {
namespace {

double value(const Summary& s, const std::string& key) {
  const auto v = s.get(key);
  EXPECT_TRUE(v.has_value()) << key;
  return v ? std::get<double>(*v) : 0.0;
}

TEST(CuttingSummary, MeansOverAllSamplesAndOverTheContactSamples) {
  const rockcut::Scene scene =
      scene::load_scene(std::filesystem::path(ROCKCUT_SOURCE_DIR) / "cases/cutting/dry_reduced.pbtxt",
                        {})
          .scene;
  CuttingSummary summary(scene, {});
  ASSERT_TRUE(summary.active());
  // steady_after_m 0: two cutting depths (40 mm) in. One sample before, then four: the tool cuts
  // (rock pushing back, F_x < 0), flies, cuts, flies.
  const double steady = 2 * scene.dem().tool().cutting_depth_m();
  auto sample = [&](double travel_m, double fx, double fy) {
    summary.observe({{"tool_force_x_n_per_m", fx}, {"tool_force_y_n_per_m", fy},
                     {"tool_travel_m", travel_m}});
  };
  sample(steady - 1e-3, -9e9, 9e9);  // before the steady part: ignored
  sample(steady, -100e3, -10e3);
  sample(steady + 1e-3, 0.0, 0.0);
  sample(steady + 2e-3, -300e3, -30e3);
  sample(steady + 3e-3, 0.0, 0.0);
  Summary s;
  summary.write(s);
  EXPECT_DOUBLE_EQ(value(s, "force_horizontal_mean_n_per_m"), 100e3);             // 400 / 4
  EXPECT_DOUBLE_EQ(value(s, "force_horizontal_mean_in_contact_n_per_m"), 200e3);  // 400 / 2
  EXPECT_DOUBLE_EQ(value(s, "force_vertical_mean_n_per_m"), -10e3);
  EXPECT_DOUBLE_EQ(value(s, "force_vertical_mean_in_contact_n_per_m"), -20e3);
  EXPECT_DOUBLE_EQ(value(s, "tool_contact_fraction"), 0.5);
  EXPECT_DOUBLE_EQ(value(s, "force_horizontal_peak_n_per_m"), 300e3);
  // E_sp = F_h / d: 100 kN/m over 20 mm = 5 MPa.
  EXPECT_DOUBLE_EQ(value(s, "specific_energy_mpa"), 100e3 / scene.dem().tool().cutting_depth_m() * 1e-6);
}

}  // namespace
}  // namespace rockcut::coupler
