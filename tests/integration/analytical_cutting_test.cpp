// The analytical models beside a real cut (coupler/observers/analytical_cutting.cpp): the small dry
// cut of cutting_test.cpp, whose scene (cases/cutting/dry_reduced.pbtxt) takes the default rock's
// `rock` block, carries the `analytical_*` keys with the models' values for the scene's inputs and
// the DEM/model ratios; the same scene without its `rock` block carries none.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "integration/process_helpers.hpp"
#include "integration/small_cuts.hpp"
#include "integration/summary_values.hpp"
#include "support/summary_parser.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;

double rad(double deg) { return deg * 3.14159265358979323846 / 180.0; }

TEST(AnalyticalCutting, ACutWithARockCarriesEachModelAndTheRatios) {
  const CouplerRun r = run_coupler(kDryReducedScene, kSmallDryCut, fresh_dir("analytical_cut"),
                                   std::chrono::milliseconds(60000));
  ASSERT_EQ(r.code, 0) << r.err;
  const coupler::Summary s = coupler::read_summary(r.out / "summary.json");
  // The scene's inputs: cases/rock/default_rock.pbtxt (BTS 2.55 MPa, c 2.966 MPa, phi 43.48 deg),
  // dem.contact.friction 1 (delta = 45 deg), a 60 deg tool 20 mm deep, dry.
  const double bts = 2.55e6, c = 2.966e6, phi = 43.48, delta = 45.0, alpha = 60.0, d = 0.02;
  EXPECT_DOUBLE_EQ(number(s, "analytical_tool_friction_angle_deg"), delta);
  // Evans at 60 deg: 2 sigma_t d (evans_tensile_chip.hpp, theta = 30 deg).
  EXPECT_NEAR(number(s, "analytical_evans_force_horizontal_n_per_m"), 2.0 * bts * d, 1e-6);
  // Merchant's closed form, written out here from the scene's numbers.
  const double merchant = 2.0 * c * d * std::cos(rad(phi)) * std::sin(rad(alpha + delta)) /
                          (1.0 + std::cos(rad(alpha + delta + phi)));
  EXPECT_NEAR(number(s, "analytical_merchant_force_horizontal_n_per_m"), merchant, 1e-9 * merchant);
  EXPECT_NEAR(number(s, "analytical_merchant_shear_angle_deg"), (180.0 - alpha - delta - phi) / 2.0,
              1e-9);
  // Nishimatsu with his fit n = 11.3 - 0.18 * 30 = 5.9: Merchant's force over n + 1.
  EXPECT_NEAR(number(s, "analytical_nishimatsu_exponent"), 5.9, 1e-12);
  EXPECT_NEAR(number(s, "analytical_nishimatsu_force_horizontal_n_per_m"), merchant / 6.9,
              1e-9 * merchant);
  // Dry: no pore water, so the hyperbaric bound is the drained force.
  EXPECT_EQ(number(s, "analytical_hyperbaric_under_pressure_pa"), 0.0);
  EXPECT_NEAR(number(s, "analytical_hyperbaric_force_horizontal_n_per_m"), merchant, 1e-9 * merchant);
  EXPECT_EQ(text(s, "analytical_failure_mode"), "shear");
  // The ratios are the DEM's own mean and peak over each model's force.
  const double mean = number(s, "force_horizontal_mean_n_per_m");
  const double peak = number(s, "force_horizontal_peak_n_per_m");
  ASSERT_GT(mean, 0.0);
  for (const char* model : {"evans", "nishimatsu", "merchant", "hyperbaric"}) {
    const std::string key = std::string("analytical_") + model;
    const double f = number(s, key + "_force_horizontal_n_per_m");
    EXPECT_DOUBLE_EQ(number(s, key + "_ratio_mean"), mean / f) << model;
    EXPECT_DOUBLE_EQ(number(s, key + "_ratio_peak"), peak / f) << model;
  }
  // The DEM's own figures: E_sp = F_h / d in MPa, and the p95 between the mean and the peak.
  EXPECT_DOUBLE_EQ(number(s, "specific_energy_mpa"), mean / d * 1e-6);
  EXPECT_LE(number(s, "force_horizontal_p95_n_per_m"), peak);
  EXPECT_GT(number(s, "force_horizontal_std_n_per_m"), 0.0);
}

TEST(AnalyticalCutting, ACutWithoutARockHasNoAnalyticalKeys) {
  // The effective scene (bases merged) without its rock block, as a self-contained file.
  const fs::path dir = fresh_dir("analytical_no_rock");
  std::string text_out;
  ASSERT_EQ(
      run({bin("coupler"), "validate", kDryReducedScene, "--print"}, dir, "validate", &text_out),
      0);
  // The first line is validate's verdict ("...: ok (dry, ...)"), the scene follows.
  text_out.erase(0, text_out.find('\n') + 1);
  const auto begin = text_out.find("rock {");
  ASSERT_NE(begin, std::string::npos) << "the shipped scene takes the default rock's block";
  const auto end = text_out.find("}\n", begin);
  ASSERT_NE(end, std::string::npos);
  text_out.erase(begin, end + 2 - begin);
  ASSERT_EQ(text_out.find("rock {"), std::string::npos);
  const fs::path scene = dir / "no_rock.pbtxt";
  std::ofstream(scene) << text_out;
  const CouplerRun r =
      run_coupler(scene.string(), kSmallDryCut, dir, std::chrono::milliseconds(60000));
  ASSERT_EQ(r.code, 0) << r.err;
  const coupler::Summary s = coupler::read_summary(r.out / "summary.json");
  EXPECT_GT(number(s, "force_horizontal_mean_n_per_m"), 0.0);
  for (const auto& [key, value] : s.entries()) {
    EXPECT_NE(key.rfind("analytical_", 0), 0u) << key;
  }
}

}  // namespace
}  // namespace rockcut::test
