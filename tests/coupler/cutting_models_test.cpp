// The analytical cutting models (coupler/cutting_models/) against a published worked example and
// against limits that reduce by hand to textbook expressions. No expected value here comes from
// running our own code.
#include <gtest/gtest.h>

#include <cmath>

#include "cutting_models/evans_tensile_chip.hpp"
#include "cutting_models/failure_mode.hpp"
#include "cutting_models/hyperbaric_flow_type.hpp"
#include "cutting_models/merchant_flow_type.hpp"
#include "cutting_models/nishimatsu_shear_plane.hpp"

namespace rockcut::coupler::cutting_models {
namespace {

constexpr double kC = 3e6;        // cohesion [Pa]
constexpr double kBts = 2.5e6;    // tensile strength [Pa]
constexpr double kDepth = 0.02;   // cut depth [m]

// ---- Evans ------------------------------------------------------------------------------------

TEST(EvansTensileChip, ZeroDepthGivesZeroForce) {
  const CuttingForce f = evans_tensile_chip(kBts, 60.0, 0.0);
  EXPECT_EQ(f.horizontal_n_per_m, 0.0);
  EXPECT_EQ(f.vertical_up_n_per_m, 0.0);
}

TEST(EvansTensileChip, SixtyDegreeBladeGivesTwiceTensileStrengthTimesDepth) {
  // alpha = 60 deg: alpha_r = 30, theta = (90 - 30) / 2 = 30 deg, sin = 1/2, so
  // F = 2 sigma_t d (1/2) / (1/2) = 2 sigma_t d exactly; the force is normal to the frictionless
  // face, pulling the tool down by F cot(60) = F / sqrt(3).
  const CuttingForce f = evans_tensile_chip(kBts, 60.0, kDepth);
  EXPECT_NEAR(f.horizontal_n_per_m, 2.0 * kBts * kDepth, 1e-9 * kBts * kDepth);
  EXPECT_NEAR(f.vertical_up_n_per_m, -2.0 * kBts * kDepth / std::sqrt(3.0), 1e-9 * kBts * kDepth);
}

TEST(EvansTensileChip, VerticalFaceGivesTwoPlusTwoRootTwo) {
  // alpha = 90 deg (zero rake): theta = 45 deg, F = 2 sigma_t d (sqrt2/2) / (1 - sqrt2/2)
  // = (2 + 2 sqrt2) sigma_t d; a horizontal normal force, no vertical component.
  const CuttingForce f = evans_tensile_chip(kBts, 90.0, kDepth);
  EXPECT_NEAR(f.horizontal_n_per_m, (2.0 + 2.0 * std::sqrt(2.0)) * kBts * kDepth, 1e-9 * kBts);
  EXPECT_NEAR(f.vertical_up_n_per_m, 0.0, 1e-9 * kBts);
}

// ---- Merchant / Miedema flow type --------------------------------------------------------------

TEST(MerchantFlowType, TextbookMachiningExample) {
  // A published worked example of Merchant's minimum-force theory (phi = 0): a machining textbook's
  // Sample Problem 3, p. 193, transcribed as FOSSEE Scilab Textbook Companion 3250, example 4.3
  // (github.com/FOSSEE/Scilab-TBC-Uploads, 3250/CH4/EX4.3): rake angle 10 deg, friction
  // coefficient 0.5, uncut thickness 0.2 mm, width 2 mm, shear strength 400 N/mm^2; the book
  // prints a cutting force of 420 N and a thrust of 125 N. In Miedema's convention the blade angle
  // is 90 - 10 = 80 deg and delta = atan(0.5). Tolerance 2.5 %: the book's answers are rounded to
  // two-three figures from rounded intermediate values (its own chain of formulas, evaluated
  // without rounding, gives 429 N and 128 N); a wrong friction or angle convention moves the force
  // by far more (delta = 0 gives 269 N, the rake angle taken for the blade angle 106 N).
  const double width_m = 0.002;
  const FlowTypeForce r = merchant_flow_type(400e6, 0.0, std::atan(0.5) * 180.0 / kPi, 80.0, 0.2e-3);
  EXPECT_NEAR(r.force.horizontal_n_per_m * width_m, 420.0, 0.025 * 420.0);
  // The thrust pushes the tool away from the work (up): positive in our convention.
  EXPECT_NEAR(r.force.vertical_up_n_per_m * width_m, 125.0, 0.025 * 125.0);
  // Merchant's shear angle: 45 + (alpha_r - lambda) / 2 = 45 + (10 - 26.565) / 2 = 36.72 deg.
  EXPECT_NEAR(r.shear_angle_deg, 45.0 + (10.0 - std::atan(0.5) * 180.0 / kPi) / 2.0, 1e-9);
}

TEST(MerchantFlowType, VerticalFrictionlessToolInPureCohesionGivesTwoCohesionTimesDepth) {
  // alpha = 90, delta = phi = 0: the shear plane at 45 deg carries c h sqrt2 along it; the
  // horizontal force is 2 c h, the vertical zero (the textbook plane-strain result).
  const FlowTypeForce r = merchant_flow_type(kC, 0.0, 0.0, 90.0, kDepth);
  EXPECT_NEAR(r.shear_angle_deg, 45.0, 1e-12);
  EXPECT_NEAR(r.force.horizontal_n_per_m, 2.0 * kC * kDepth, 1e-9 * kC * kDepth);
  EXPECT_NEAR(r.force.vertical_up_n_per_m, 0.0, 1e-9 * kC * kDepth);
}

TEST(MerchantFlowType, ZeroDepthGivesZeroForceAndNoShearPlaneBeyondTheLimit) {
  EXPECT_EQ(merchant_flow_type(kC, 30.0, 30.0, 60.0, 0.0).force.horizontal_n_per_m, 0.0);
  // alpha + delta + phi >= 180 deg: no shear plane exists.
  EXPECT_TRUE(std::isnan(merchant_flow_type(kC, 60.0, 60.0, 60.0, kDepth).force.horizontal_n_per_m));
}

TEST(MerchantFlowType, ClosedFormIsTheMinimumOfTheEquilibrium) {
  // The closed form (eq. 3-33) against the equilibrium evaluated on both sides of its beta.
  const FlowTypeForce r = merchant_flow_type(kC, 43.0, 45.0, 60.0, kDepth);
  for (double step : {-1.0, 1.0}) {
    const CuttingForce off = flow_type_at_shear_angle(kC, 43.0, 45.0, 60.0, kDepth, 0.0, 0.0,
                                                      r.shear_angle_deg + step);
    EXPECT_GT(off.horizontal_n_per_m, r.force.horizontal_n_per_m);
  }
  // 2 c h cos(phi) sin(alpha+delta) / (1 + cos(alpha+delta+phi)), evaluated by hand in degrees.
  const double expected = 2.0 * kC * kDepth * std::cos(radians(43.0)) * std::sin(radians(105.0)) /
                          (1.0 + std::cos(radians(148.0)));
  EXPECT_NEAR(r.force.horizontal_n_per_m, expected, 1e-9 * expected);
}

// ---- Nishimatsu ---------------------------------------------------------------------------------

TEST(NishimatsuShearPlane, UniformStressIsMerchantsMinimum) {
  // n = 0: Nishimatsu's formula in rake angles equals Merchant's closed form in blade angles
  // (the identity in nishimatsu_shear_plane.hpp), here for the default rock's angles and a few more.
  for (double alpha : {40.0, 60.0, 75.0, 90.0}) {
    const CuttingForce n = nishimatsu_shear_plane(kC, 43.5, 45.0, alpha, kDepth, 0.0);
    const FlowTypeForce m = merchant_flow_type(kC, 43.5, 45.0, alpha, kDepth);
    EXPECT_NEAR(n.horizontal_n_per_m, m.force.horizontal_n_per_m, 1e-9 * m.force.horizontal_n_per_m);
    EXPECT_NEAR(n.vertical_up_n_per_m, m.force.vertical_up_n_per_m,
                1e-9 * m.force.horizontal_n_per_m);
  }
}

TEST(NishimatsuShearPlane, ExponentDividesTheForceByNPlusOne) {
  const double f0 = nishimatsu_shear_plane(kC, 30.0, 20.0, 60.0, kDepth, 0.0).horizontal_n_per_m;
  const double f5 = nishimatsu_shear_plane(kC, 30.0, 20.0, 60.0, kDepth, 5.0).horizontal_n_per_m;
  EXPECT_NEAR(f5, f0 / 6.0, 1e-12 * f0);
  EXPECT_EQ(nishimatsu_shear_plane(kC, 30.0, 20.0, 60.0, 0.0, 5.0).horizontal_n_per_m, 0.0);
  // Zero rake, no friction at all, n = 0: 2 c d cos0 cos0 / (1 - sin0) = 2 c d.
  EXPECT_NEAR(nishimatsu_shear_plane(kC, 0.0, 0.0, 90.0, kDepth, 0.0).horizontal_n_per_m,
              2.0 * kC * kDepth, 1e-9 * kC * kDepth);
}

TEST(NishimatsuShearPlane, ExponentFitAtThirtyDegreesRake) {
  // Nishimatsu (1972): n = 11.3 - 0.18 alpha_r; at alpha_r = 30 deg, 11.3 - 5.4 = 5.9.
  EXPECT_NEAR(nishimatsu_exponent_fit(30.0), 5.9, 1e-12);
  EXPECT_NEAR(nishimatsu_exponent_fit(rake_angle_deg(60.0)), 5.9, 1e-12);
}

// ---- Miedema's failure criterion ----------------------------------------------------------------

TEST(MiedemaFailureMode, PureCohesionWithoutFrictionReducesToTanHalfAlpha) {
  // phi = delta = 0: beta = 90 - alpha/2, so sigma_n = c tan(alpha/2) and, tau being c, the Mohr
  // circle has centre sigma_n and radius c: sigma_min = c (tan(alpha/2) - 1). At alpha = 90 the
  // principal stresses are 0 and 2c (pure shear about c).
  for (double alpha : {20.0, 45.0, 60.0, 90.0}) {
    const FailureMode m = miedema_failure_mode(kC, 0.0, kBts, 0.0, alpha);
    const double t = std::tan(radians(alpha) / 2.0);
    EXPECT_NEAR(m.shear_plane_normal_stress_pa, kC * t, 1e-9 * kC);
    EXPECT_NEAR(m.least_principal_stress_pa, kC * (t - 1.0), 1e-9 * kC);
  }
}

TEST(MiedemaFailureMode, ModesFollowTheTensileStrength) {
  // alpha = 20, phi = delta = 0: sigma_min = c (tan 10 - 1) = -0.8237 c, sigma_n = +0.1763 c.
  EXPECT_EQ(miedema_failure_mode(kC, 0.0, 0.5 * kC, 0.0, 20.0).mode, "tensile");
  EXPECT_EQ(miedema_failure_mode(kC, 0.0, 0.8 * kC, 0.0, 20.0).mode, "tensile");
  EXPECT_EQ(miedema_failure_mode(kC, 0.0, 0.85 * kC, 0.0, 20.0).mode, "shear");
  // alpha = 20, delta = 0, phi = 40: beta = 60, sigma_n = -c cos(80) cos(40) / sin(120)
  // = -0.1536 c: the shear plane itself is in tension, and so below any small BTS.
  const FailureMode m = miedema_failure_mode(kC, 40.0, 0.1 * kC, 0.0, 20.0);
  EXPECT_NEAR(m.shear_plane_normal_stress_pa,
              -kC * std::cos(radians(80.0)) * std::cos(radians(40.0)) / std::sin(radians(120.0)),
              1e-9 * kC);
  EXPECT_LT(m.least_principal_stress_pa, m.shear_plane_normal_stress_pa);
  EXPECT_EQ(m.mode, "tensile");
  EXPECT_EQ(miedema_failure_mode(kC, 60.0, kBts, 60.0, 60.0).mode, "none");
}

// Miedema, The Delft Sand, Clay & Rock Cutting Model (2019a): section 8.9 (figures 8-49 to 8-52)
// and the exercise of figure 16-11: UCS 100 MPa, phi 20 deg, blade angle 60 deg (delta 2/3 phi, as
// in exercise 16.8.5 below). The book's Mohr circle of the shear plane has radius 45.59 MPa and
// least principal stress -8.48 MPa; "the transition tensile failure/shear failure occurs at a
// tensile strength of about -8.5 MPa", and with -5 MPa (figure 16-11) the rock fails in tension.
// Tolerance 0.005 MPa: the book prints two decimals.
TEST(MiedemaFailureMode, BookTransitionAtEightAndAHalfPercentOfTheUcs) {
  const double ucs = 100e6, phi = 20.0, delta = 2.0 * phi / 3.0, alpha = 60.0;
  const double c = ucs * (1.0 - std::sin(radians(phi))) / (2.0 * std::cos(radians(phi)));
  const FailureMode m = miedema_failure_mode(c, phi, 5e6, delta, alpha);
  const double tau = c + m.shear_plane_normal_stress_pa * std::tan(radians(phi));
  EXPECT_NEAR(tau / std::cos(radians(phi)), 45.59e6, 0.005e6);
  EXPECT_NEAR(m.least_principal_stress_pa, -8.48e6, 0.005e6);
  EXPECT_EQ(m.mode, "tensile");
  EXPECT_EQ(miedema_failure_mode(c, phi, 8.4e6, delta, alpha).mode, "tensile");
  EXPECT_EQ(miedema_failure_mode(c, phi, 8.6e6, delta, alpha).mode, "shear");
  EXPECT_EQ(miedema_failure_mode(c, phi, 20e6, delta, alpha).mode, "shear");
}

// Miedema, The Delft Sand, Clay & Rock Cutting Model (2019a), exercise 16.8.5 "Cutting forces &
// mechanisms" (the chapter of exercises): a rock of UCS 60 MPa and tensile strength 3 MPa, phi 20
// deg, delta 13.33 deg, blade angle 60 deg. The book's worked numbers: shear angle 43.33 deg,
// cohesion c = UCS (1 - sin phi) / (2 cos phi) = 21 MPa, normal stress on the shear plane 12.9 MPa,
// shear stress 25.7 MPa, Mohr circle centre 22.27 MPa and radius 27.35 MPa, least principal stress
// -5.09 MPa, below -3 MPa: the rock fails in tension. Tolerances: the book's rounding (0.05 MPa on
// the one-decimal stresses, 0.01 MPa on the two-decimal one, 0.5 MPa on the integer cohesion).
TEST(MiedemaFailureMode, BookExerciseSixtyMegapascalRock) {
  // The book's delta 13.33 deg is 2/3 of phi, the usual choice, which its 43.33 deg also implies.
  const double ucs = 60e6, phi = 20.0, delta = 2.0 * phi / 3.0, alpha = 60.0, bts = 3e6;
  const double c = ucs * (1.0 - std::sin(radians(phi))) / (2.0 * std::cos(radians(phi)));
  EXPECT_NEAR(c, 21e6, 0.5e6);
  EXPECT_NEAR(merchant_shear_angle_deg(phi, delta, alpha), 43.33, 0.005);
  const FailureMode m = miedema_failure_mode(c, phi, bts, delta, alpha);
  EXPECT_NEAR(m.shear_plane_normal_stress_pa, 12.9e6, 0.05e6);
  EXPECT_NEAR(c + m.shear_plane_normal_stress_pa * std::tan(radians(phi)), 25.7e6, 0.05e6);
  EXPECT_NEAR(m.least_principal_stress_pa, -5.09e6, 0.01e6);
  EXPECT_EQ(m.mode, "tensile");  // the circle reaches the tension cut-off: tensile failure
}

// ---- Hyperbaric --------------------------------------------------------------------------------

TEST(HyperbaricFlowType, CavitationBoundIsTheAbsolutePressure) {
  // p_atm + rho g z - p_vapour; ~ rho g (z + 10): within 2 % at the surface, 0.02 % at 1000 m.
  EXPECT_NEAR(cavitation_under_pressure_pa(0.0, 1025.0, 9.81, 101325.0, 2340.0), 98985.0, 1e-6);
  const double at_1000 = cavitation_under_pressure_pa(1000.0, 1025.0, 9.81, 101325.0, 2340.0);
  EXPECT_NEAR(at_1000, 101325.0 + 1025.0 * 9.81 * 1000.0 - 2340.0, 1e-6);
  EXPECT_NEAR(at_1000, 1025.0 * 9.81 * 1010.0, 2e-4 * at_1000);
  EXPECT_EQ(cavitation_under_pressure_pa(0.0, 1025.0, 9.81, 0.0, 2340.0), 0.0);
}

TEST(HyperbaricFlowType, WithoutUnderPressureItIsMerchant) {
  // dp = 0 (dry, or drained: the water follows the dilation): the numerical minimum over beta is
  // the closed form's.
  const FlowTypeForce h = hyperbaric_flow_type(kC, 43.5, 45.0, 60.0, kDepth, 0.05, 0.0);
  const FlowTypeForce m = merchant_flow_type(kC, 43.5, 45.0, 60.0, kDepth);
  EXPECT_NEAR(h.shear_angle_deg, m.shear_angle_deg, 1e-6);
  EXPECT_NEAR(h.force.horizontal_n_per_m, m.force.horizontal_n_per_m, 1e-10 * m.force.horizontal_n_per_m);
  EXPECT_NEAR(h.force.vertical_up_n_per_m, m.force.vertical_up_n_per_m, 1e-10 * m.force.horizontal_n_per_m);
}

TEST(HyperbaricFlowType, UnderPressureOnTheShearPlaneActsAsCohesion) {
  // h_b = 0 (no blade under-pressure): K2 = (dp sin(phi) + c cos(phi)) h / (sin(beta) sin(...)),
  // i.e. the dry force with c + dp tan(phi) (effective stress), at the same beta.
  const double dp = 10e6;
  const FlowTypeForce h = hyperbaric_flow_type(kC, 30.0, 20.0, 60.0, kDepth, 0.0, dp);
  const FlowTypeForce m =
      merchant_flow_type(kC + dp * std::tan(radians(30.0)), 30.0, 20.0, 60.0, kDepth);
  EXPECT_NEAR(h.force.horizontal_n_per_m, m.force.horizontal_n_per_m, 1e-10 * m.force.horizontal_n_per_m);
  EXPECT_NEAR(h.shear_angle_deg, m.shear_angle_deg, 1e-6);
}

TEST(HyperbaricFlowType, BookAppendixCavitatingCoefficients) {
  // Miedema, The Delft Sand, Clay & Rock Cutting Model, appendices H, I and J (LibreTexts 17.8-17.10):
  // the cavitating flow type without cohesion, h_b / h_i = 1, tabulated as the shear angle beta
  // and the coefficients d1 = F_h / (rho_w g (z + 10) w h_i), d2 = F_v,down / (the same), per
  // blade angle alpha, blade friction delta and internal friction phi. Our dp stands for
  // rho_w g (z + 10), so dp = 1 Pa, h = h_b = 1 m gives d1 and -d2 directly.
  struct Row {
    double alpha, delta, phi, beta, d1, d2;
  };
  const Row rows[] = {{15, 15, 32, 37.217, 1.390, 0.409}, {30, 30, 42, 28.859, 2.833, 0.483},
                      {45, 15, 47, 32.412, 2.365, 0.945}, {60, 15, 42, 28.608, 2.883, 0.465},
                      {60, 30, 52, 17.208, 8.991, -0.570}};
  for (const Row& r : rows) {
    const FlowTypeForce f = hyperbaric_flow_type(0.0, r.phi, r.delta, r.alpha, 1.0, 1.0, 1.0);
    EXPECT_NEAR(f.shear_angle_deg, r.beta, 0.05) << r.alpha << " " << r.delta << " " << r.phi;
    EXPECT_NEAR(f.force.horizontal_n_per_m, r.d1, 0.005 * r.d1) << r.alpha << " " << r.phi;
    EXPECT_NEAR(-f.force.vertical_up_n_per_m, r.d2, 0.01) << r.alpha << " " << r.phi;
    // The tables are reproduced to their printed precision when degrees become radians with
    // pi = 3.14 (their d2 at alpha + delta = 90 deg drifts from -cot(60 deg) = -0.5774 with phi,
    // which exact arithmetic cannot do): the book's rounding, not a different equation.
    const double k = 3.14 / std::acos(-1.0);
    const FlowTypeForce b =
        hyperbaric_flow_type(0.0, r.phi * k, r.delta * k, r.alpha * k, 1.0, 1.0, 1.0);
    EXPECT_NEAR(b.shear_angle_deg / k, r.beta, 6e-4) << r.alpha << " " << r.delta << " " << r.phi;
    EXPECT_NEAR(b.force.horizontal_n_per_m, r.d1, 6e-4) << r.alpha << " " << r.phi;
    EXPECT_NEAR(-b.force.vertical_up_n_per_m, r.d2, 6e-4) << r.alpha << " " << r.phi;
  }
}

TEST(HyperbaricFlowType, ForceGrowsWithDepthUpToTheCavitationBound) {
  // The under-pressure at the cavitation bound rises with depth, and so does the force; the blade's
  // under-pressure only adds (through friction on the blade) for delta > 0.
  double previous = 0.0;
  for (double z : {0.0, 10.0, 100.0, 1000.0, 2000.0}) {
    const double dp = cavitation_under_pressure_pa(z, 1025.0, 9.81, 101325.0, 2340.0);
    const double f = hyperbaric_flow_type(kC, 43.5, 45.0, 60.0, kDepth, 0.05, dp).force.horizontal_n_per_m;
    EXPECT_GT(f, previous);
    previous = f;
  }
  EXPECT_TRUE(std::isnan(hyperbaric_flow_type(kC, 60.0, 60.0, 60.0, kDepth, 0.05, 1e6).force.horizontal_n_per_m));
}

}  // namespace
}  // namespace rockcut::coupler::cutting_models
