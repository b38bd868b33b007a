// Calibration results from a stress-strain series: UCS, E at 40-60 % of the failure peak, nu, BTS.
#include <gtest/gtest.h>

#include <numbers>

#include "observers/calibration_summary.hpp"

namespace rockcut::coupler {
namespace {

rockcut::Scene ucs_scene() {
  rockcut::Scene s;
  s.mutable_dem()->mutable_loading_test()->set_kind("ucs");
  return s;
}

std::vector<std::pair<std::string, double>> sample(double strain, double stress, double lateral) {
  return {{"axial_strain", strain}, {"axial_stress_pa", stress}, {"lateral_strain", lateral}};
}

double number(const Summary& s, const std::string& key) { return std::get<double>(*s.get(key)); }

TEST(CalibrationSummary, LinearElasticThenBrittle) {
  CalibrationSummary c(ucs_scene());
  const double e = 5.5e9, nu = 0.22;
  for (int k = 0; k <= 100; ++k) {
    const double strain = 2.5e-5 * k;  // peak 13.75 MPa at k = 100
    c.observe(sample(strain, e * strain, nu * strain));  // compression +, extension +
  }
  c.observe(sample(2.6e-3, 2e6, 1e-3));  // failure
  Summary out;
  c.write(out);
  // Exact data: the least-squares fit reproduces E and nu to round-off.
  EXPECT_NEAR(number(out, "ucs_pa"), e * 2.5e-3, 1e-6);
  EXPECT_NEAR(number(out, "youngs_modulus_pa") / e, 1.0, 1e-12);
  EXPECT_NEAR(number(out, "poisson_ratio"), nu, 1e-12);
}

// Biaxial: the peak is the deviator's, sigma_1 = deviator + the sigma_3 of that sample, and the
// residual strength is the mean axial stress over the last fifth of the strain after the peak.
TEST(CalibrationSummary, BiaxialPeakIsTheDeviatorsAndTheResidualTheLastFifthsMean) {
  rockcut::Scene scene;
  scene.mutable_dem()->mutable_loading_test()->set_kind("biaxial");
  CalibrationSummary c(scene);
  const double e = 5e9, confining = 2e6;
  for (int k = 0; k <= 100; ++k) {  // deviator E eps up to 10 MPa at eps 2e-3
    const double strain = 2e-5 * k;
    c.observe({{"axial_strain", strain},
               {"axial_stress_pa", confining + e * strain},
               {"lateral_strain", 0.0},
               {"lateral_stress_pa", confining}});
  }
  // Softening to a residual deviator of 4 MPa at strains 3.1e-3 .. 7.1e-3 (0.25e-3 apart).
  for (int k = 0; k <= 16; ++k) {
    c.observe({{"axial_strain", 3.1e-3 + 2.5e-4 * k},
               {"axial_stress_pa", confining + 4e6 + (k % 2 ? 1e5 : -1e5)},
               {"lateral_strain", 0.0},
               {"lateral_stress_pa", confining}});
  }
  Summary out;
  c.write(out);
  EXPECT_FALSE(out.get("ucs_pa").has_value());
  EXPECT_NEAR(number(out, "peak_deviator_stress_pa"), 1e7, 1e-6);
  EXPECT_NEAR(number(out, "peak_axial_stress_pa"), 1.2e7, 1e-6);
  EXPECT_NEAR(number(out, "confining_stress_pa"), confining, 1e-9);
  EXPECT_NEAR(number(out, "peak_axial_strain"), 2e-3, 1e-15);
  // The last fifth of 2e-3 .. 7.1e-3: strains from 6.08e-3, samples k = 12 .. 16 (- + - + -:
  // mean 4 MPa - 1e5 / 5).
  EXPECT_NEAR(number(out, "residual_axial_stress_pa"), confining + 4e6 - 2e4, 1e-6);
  EXPECT_NEAR(number(out, "youngs_modulus_pa") / e, 1.0, 1e-12);
}

TEST(CalibrationSummary, ModulusAndPoissonRatioComeFromTheGaugeNotThePlatens) {
  // The platens also close the seating gap of the rough ends (half the platen strain here); the
  // gauge on the specimen's middle half sees only the specimen's strain.
  CalibrationSummary c(ucs_scene());
  const double e = 5.5e9, nu = 0.22;
  for (int k = 0; k <= 100; ++k) {
    const double gauge = 2.5e-5 * k;
    c.observe({{"axial_strain", 2.0 * gauge},
               {"axial_stress_pa", e * gauge},
               {"lateral_strain", nu * gauge},
               {"axial_strain_gauge", gauge}});
  }
  Summary out;
  c.write(out);
  EXPECT_NEAR(number(out, "youngs_modulus_pa") / e, 1.0, 1e-12);
  EXPECT_NEAR(number(out, "poisson_ratio"), nu, 1e-12);
}

TEST(CalibrationSummary, StrengthIsTheFirstFailurePeakNotALaterCompaction) {
  CalibrationSummary c(ucs_scene());
  for (int k = 0; k <= 10; ++k) c.observe(sample(1e-4 * k, 1e6 * k, 0.0));  // peak 10 MPa
  c.observe(sample(1.1e-3, 7e6, 0.0));    // drops below 80 %: failed
  c.observe(sample(3.0e-3, 14e6, 0.0));   // the rubble compacts to a higher load later
  Summary out;
  c.write(out);
  EXPECT_EQ(number(out, "ucs_pa"), 10e6);
  EXPECT_NEAR(number(out, "youngs_modulus_pa"), 1e10, 1e-3);
}

TEST(CalibrationSummary, SeatingSlipsBelowAFifthOfTheLargestLoadAreNotFailure) {
  // A few end discs carry the first load and slip (0.5 -> 0.2 MPa, a 60 % drop) before the
  // platens seat; the specimen then loads elastically to its failure at 10 MPa.
  CalibrationSummary c(ucs_scene());
  c.observe(sample(0.0, 0.0, 0.0));
  c.observe(sample(1e-5, 0.5e6, 0.0));
  c.observe(sample(2e-5, 0.2e6, 0.0));
  for (int k = 1; k <= 20; ++k) c.observe(sample(2e-5 + 5e-5 * k, 0.2e6 + 0.49e6 * k, 0.0));
  c.observe(sample(1.2e-3, 5e6, 0.0));  // failure
  Summary out;
  c.write(out);
  EXPECT_NEAR(number(out, "ucs_pa"), 10e6, 1e-6);
  EXPECT_NEAR(number(out, "youngs_modulus_pa"), 0.98e10, 1e-3);
  // A drop at 25 % of the largest load counts: 2.5 MPa -> 1.5 MPa is failure there.
  CalibrationSummary d(ucs_scene());
  for (double load : {0.0, 2.5e6, 1.5e6, 10e6}) d.observe(sample(load / 1e10, load, 0.0));
  Summary out2;
  d.write(out2);
  EXPECT_EQ(number(out2, "ucs_pa"), 2.5e6);
}

TEST(CalibrationSummary, BrazilianTensileStrength) {
  rockcut::Scene s;
  s.mutable_dem()->mutable_loading_test()->set_kind("brazilian");
  s.mutable_dem()->mutable_specimen()->set_diameter_m(0.04);
  CalibrationSummary c(s);
  // Local crushing at the platens (1e5 -> 4e4) with the disc still closed, a partial crack
  // (1.3e5 -> 0.8e5, opening 6e-4), the reloading to the split (1.6e5), the opening, then the
  // halves crushed to a higher load (1.9e5).
  const double forces[] = {0.0, 5e4, 1e5, 4e4, 1.3e5, 0.8e5, 1.6e5, 2e4, 1.9e5};
  const double opening[] = {0.0, 1e-4, 2e-4, 2e-4, 3e-4, 6e-4, 8e-4, 2e-3, 3e-2};
  for (int k = 0; k < 9; ++k) {
    // stop_at_split (default true): the test is over at the split and not before.
    EXPECT_EQ(c.test_over(), k > 7) << k;
    c.observe({{"axial_strain", 1e-3 * k},
               {"platen_force_n_per_m", forces[k]},
               {"lateral_strain", opening[k]}});
  }
  Summary out;
  c.write(out);
  EXPECT_NEAR(number(out, "bts_pa"), 2 * 1.6e5 / (std::numbers::pi * 0.04), 1e-6);
  EXPECT_TRUE(std::get<bool>(*out.get("split_detected")));
  EXPECT_NEAR(number(out, "split_axial_strain"), 7e-3, 1e-15);
}

TEST(CalibrationSummary, BrazilianWithoutASplitReportsTheLargestLoadAndSaysSo) {
  rockcut::Scene s;
  s.mutable_dem()->mutable_loading_test()->set_kind("brazilian");
  s.mutable_dem()->mutable_specimen()->set_diameter_m(0.04);
  CalibrationSummary c(s);
  for (double f : {0.0, 5e4, 1e5}) {
    c.observe({{"axial_strain", 0.0}, {"platen_force_n_per_m", f}, {"lateral_strain", 1e-4}});
  }
  EXPECT_FALSE(c.test_over());
  Summary out;
  c.write(out);
  EXPECT_NEAR(number(out, "bts_pa"), 2 * 1e5 / (std::numbers::pi * 0.04), 1e-6);
  EXPECT_FALSE(std::get<bool>(*out.get("split_detected")));
}

TEST(CalibrationSummary, InactiveWithoutALoadingTest) {
  CalibrationSummary c(rockcut::Scene{});
  EXPECT_FALSE(c.active());
  Summary out;
  c.write(out);
  EXPECT_TRUE(out.entries().empty());
}

}  // namespace
}  // namespace rockcut::coupler
