// Cavitation (paper eq. 22; DESIGN section 4): the pore pressure cannot fall below the vapour
// pressure p_min. A particle at p_min is held there, and only increases of its pressure pass:
//   p_i < p_min  =>  p_i = p_min  and  dp_i/dt = max(dp_i/dt, 0).
// The one statement of the clamp, shared by the explicit model (forward Euler,
// models/explicit_model.cpp), the implicit model's active set (sp/implicit_system.cpp) and the count
// of cavitated particles (models/pore_pressure_model.cpp).
#pragma once

#include <algorithm>

namespace rockcut::fluid::sp {

/// True when pressure p [Pa] sits at (or below) the vapour pressure: the particle is cavitated.
inline bool at_vapour_pressure(double p_pa, double p_min_pa) { return p_pa <= p_min_pa; }

/// True when p [Pa] lies below the vapour pressure and must be raised to it.
inline bool below_vapour_pressure(double p_pa, double p_min_pa) { return p_pa < p_min_pa; }

/// Eq. 22 on a forward-Euler step of dp/dt = rate over dt_s: at the clamp only increases pass,
/// and the new pressure is never below p_min.
inline double cavitation_limited_step(double p_pa, double rate_pa_s, double dt_s,
                                      double p_min_pa) {
  if (at_vapour_pressure(p_pa, p_min_pa)) rate_pa_s = std::max(rate_pa_s, 0.0);
  return std::max(p_pa + dt_s * rate_pa_s, p_min_pa);
}

}  // namespace rockcut::fluid::sp
