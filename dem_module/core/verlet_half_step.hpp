// The velocity-Verlet half steps (paper eqs. 5-8; eq. 8's v^{i+1/2} is a typo for v^{n+1/2},
// DESIGN section 4), for translation and rotation alike:
//   eq. 6  v^{n+1/2} = v^n + a^n dt/2                  (half kick)
//   eq. 5  x^{n+1}   = x^n + v^{n+1/2} dt              (drift; eq. 5 once eq. 6 is inserted)
//   eq. 7  a^{n+1}   = F^{n+1} / m                     (the forces at x^{n+1}, v^{n+1/2})
//   eq. 8  v^{n+1}   = v^{n+1/2} + a^{n+1} dt/2        (half kick)
// core/dem_system.cpp fuses them with the force passes (one sweep over the particles each).
// always_inline: with plain inline GCC 12 compiled the step loops differently (less vectorised).
#pragma once

namespace rockcut::dem {

/// Eqs. 6 and 8: a half kick of one velocity component (or the angular velocity) by force F
/// (or moment T) over half_dt = dt/2, with inv_mass = 1/m (or 1/I).
[[gnu::always_inline]] inline double half_kick(double velocity, double half_dt, double force, double inv_mass) {
  return velocity + half_dt * force * inv_mass;
}

/// Eq. 5: a drift of one position component by v^{n+1/2} over dt.
[[gnu::always_inline]] inline double drift(double position, double dt, double velocity_half) {
  return position + dt * velocity_half;
}

}  // namespace rockcut::dem
