// What every analytical cutting model returns, and the angle conventions they share.
//
// Forces are per metre of tool width, in the simulator's convention (coupler/observers/
// cutting_summary.hpp): `horizontal_n_per_m` resists the cut (the force the machine must push
// with), `vertical_up_n_per_m` is the rock's force on the tool, positive upwards.
//
// Angles: the scene's `dem.tool.cutting_angle_deg` is the blade angle alpha of Miedema (2014),
// "The Delft Sand, Clay & Rock Cutting Model", section 3.2, figure 3-2: the angle between the
// cutting face and the cutting direction, measured behind the tool (90 deg: a vertical face,
// small: a flat wedge). Evans and Nishimatsu use the rake angle alpha_r of the face against the
// normal to the free surface, positive when the face leans back: alpha_r = 90 deg - alpha.
#pragma once

#include <numbers>

namespace rockcut::coupler::cutting_models {

struct CuttingForce {
  double horizontal_n_per_m = 0.0;
  double vertical_up_n_per_m = 0.0;
};

inline constexpr double kPi = std::numbers::pi;
inline double radians(double deg) { return deg * kPi / 180.0; }
inline double degrees(double rad) { return rad * 180.0 / kPi; }
/// alpha_r = 90 deg - alpha (Miedema 2014, section 8.3: the rake angle of Evans and Nishimatsu).
inline double rake_angle_deg(double blade_angle_deg) { return 90.0 - blade_angle_deg; }

}  // namespace rockcut::coupler::cutting_models
