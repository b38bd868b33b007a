// A servo-controlled wall: the confining side walls of a biaxial test (Potyondy and Cundall 2004,
// section 3.1; Itasca's PFC biaxial test). After each step the wall's velocity along its inward
// normal is set to close the fraction alpha of the gap between the force the confining stress asks
// for over the loaded length and the force the discs press on the wall with:
//
//   v = alpha (sigma_c L - F) / (k_w dt),  |v| <= v_max,
//
// with k_w the stiffness of the wall's contacts as if every disc along it touched it. That is an
// upper bound of the stiffness the wall meets (the specimen behind the contacts is softer), so one
// step closes at most alpha of the gap and the servo cannot overshoot; v_max keeps the wall from
// hitting the specimen faster than the platens load it.
#pragma once

#include <algorithm>
#include <cstdint>

namespace rockcut::dem {

struct WallServo {
  std::uint32_t body = 0;            ///< the wall body it steers
  double inward_x = 1.0;             ///< inward normal along x: +1 the left wall, -1 the right
  double stress_pa = 0.0;            ///< sigma_c, the confining stress
  std::uint32_t top = 0, bottom = 0; ///< the platens whose gap is the loaded length L
  double length0_m = 0.0;            ///< L at t = 0
  double stiffness_pa = 0.0;         ///< k_w [N/m per m of overlap, per m of thickness]
  double max_speed_m_s = 0.0;        ///< v_max
  double gap_fraction = 0.5;         ///< alpha

  /// The loaded length from the platens' displacements (top moves down, bottom up).
  double loaded_length_m(double top_offset_y_m, double bottom_offset_y_m) const {
    return length0_m + top_offset_y_m - bottom_offset_y_m;
  }
  /// The wall's x velocity for the next step, from the force of the discs on it [N/m] over the
  /// step just taken.
  double velocity_x(double wall_force_x_n_per_m, double length_m, double dt_s) const {
    const double pressing_n_per_m = -inward_x * wall_force_x_n_per_m;
    const double v = gap_fraction * (stress_pa * length_m - pressing_n_per_m) / (stiffness_pa * dt_s);
    return inward_x * std::clamp(v, -max_speed_m_s, max_speed_m_s);
  }
};

}  // namespace rockcut::dem
