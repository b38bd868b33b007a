// The drag of the free water on a grain that meets it (`fluid.open_water_drag`; docs/model.md,
// "Drag in open water"). The pore-pressure model of the paper acts on the grains only through the
// pressure gradient (eq. 21), and a drained grain is held at p_hydro, so a grain thrown off the
// cut keeps its speed for ever. In water it does not: a disc of unit thickness is a circular
// cylinder in cross flow, which the still water resists with
//   F = -1/2 rho_w C_d(Re) (2 r) |v| v   [N per metre of thickness],   Re = rho_w |v| 2 r / mu,
// and C_d from White's curve fit to the measured drag of a circular cylinder,
//   C_d = 1 + 10 Re^(-2/3)   (F. M. White, Viscous Fluid Flow; within about 10 % of the
//                              measurements for 1 < Re < 2e5).
// Below Re = 1 the fit keeps F ~ |v|^(4/3), a force of less than 1e-6 N/m on these grains.
// The water is at rest in the scene's frame; only grains at the free surface (drained) feel it:
// inside the rock the pore water moves with the grains, and its flow is eq. 14's.
#pragma once

#include <cmath>

namespace rockcut::fluid::sp {

/// White's fit for a circular cylinder in cross flow at Reynolds number `re` > 0.
inline double cylinder_drag_coefficient(double re) { return 1.0 + 10.0 / std::cbrt(re * re); }

/// The drag [N/m] on a disc of radius `radius_m` moving at (vx, vy) [m/s] through still water of
/// density `rho_kg_m3` and viscosity `mu_pa_s`, added to (fx, fy).
inline void add_open_water_drag(double radius_m, double vx, double vy, double rho_kg_m3,
                                double mu_pa_s, double& fx, double& fy) {
  const double speed = std::hypot(vx, vy);
  if (!(speed > 0.0)) return;
  const double diameter = 2.0 * radius_m;
  const double re = rho_kg_m3 * speed * diameter / mu_pa_s;
  const double c = 0.5 * rho_kg_m3 * cylinder_drag_coefficient(re) * diameter * speed;
  fx -= c * vx;
  fy -= c * vy;
}

}  // namespace rockcut::fluid::sp
