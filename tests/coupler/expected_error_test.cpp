// The expected error printed at start-up: interpolation in the work-precision study's ladders
// (docs/accuracy.md) and the refusal to extrapolate beyond the coarsest setting studied.
#include <gtest/gtest.h>

#include <cmath>

#include "run/expected_error.hpp"

namespace rockcut::coupler {
namespace {

TEST(ExpectedError, FinestSettingsOfEveryLadderHaveNoErrorByDefinition) {
  std::string detail;
  const auto e = expected_force_error({0.025, 0.0705, 1.67, 0.5}, &detail);
  ASSERT_TRUE(e.has_value()) << detail;
  EXPECT_EQ(*e, 0.0);
  // Finer than the study: below what it resolves, so the finest's 0 again (paper-scale discs).
  EXPECT_EQ(*expected_force_error({0.01, 0.05, 1.0, 0.25}, nullptr), 0.0);
}

TEST(ExpectedError, CoarserThanTheStudyIsNotCovered) {
  std::string detail;
  EXPECT_FALSE(expected_force_error({0.8, 1.0, 2.5, 1.0}, &detail).has_value());
  EXPECT_NE(detail.find("dt_safety = 0.8"), std::string::npos) << detail;
  EXPECT_FALSE(expected_force_error({0.2, 1.0, 2.5, 2.0}, &detail).has_value());
  EXPECT_NE(detail.find("disc size"), std::string::npos) << detail;
}

TEST(ExpectedError, InterpolatesBetweenStudiedSettingsAndCombinesByRootSumSquare) {
  // One ladder at a time away from its finest: the result is that ladder's own error.
  const double at_02 = *expected_force_error({0.2, 0.0705, 1.67, 0.5}, nullptr);
  const double at_01 = *expected_force_error({0.1, 0.0705, 1.67, 0.5}, nullptr);
  const double at_005 = *expected_force_error({0.05, 0.0705, 1.67, 0.5}, nullptr);
  const double between = *expected_force_error({std::sqrt(0.005), 0.0705, 1.67, 0.5}, nullptr);
  ASSERT_NE(at_01, at_005);  // so that the midpoint below tells the interpolation from a step
  EXPECT_NEAR(between, 0.5 * (at_01 + at_005), 1e-12);  // linear in log(dt_safety), midpoint
  const double n_only = *expected_force_error({0.025, 1.0, 1.67, 0.5}, nullptr);
  const double both = *expected_force_error({0.2, 1.0, 1.67, 0.5}, nullptr);
  EXPECT_NEAR(both, std::hypot(at_02, n_only), 1e-12);
  // The study's values at its settings (docs/accuracy.md, set H): 8 % at
  // dt_safety 0.2, 54 % at the largest stable N, 9 % at the coupler's N = 3 (0.211 of the
  // stiffness limit, sixteen seeds), and between N = 5 (10 %) and N = 7 (33 %) linear in the log
  // of N.
  EXPECT_NEAR(at_02, 0.08, 1e-12);
  EXPECT_NEAR(n_only, 0.54, 1e-12);
  EXPECT_NEAR(*expected_force_error({0.025, 0.211, 1.67, 0.5}, nullptr), 0.09, 1e-12);
  const double n6 = 6 * 0.0705;
  const double s = std::log(n6 / 0.352) / std::log(0.493 / 0.352);
  EXPECT_NEAR(*expected_force_error({0.025, n6, 1.67, 0.5}, nullptr), 0.10 + s * (0.33 - 0.10),
              1e-12);
}

}  // namespace
}  // namespace rockcut::coupler
