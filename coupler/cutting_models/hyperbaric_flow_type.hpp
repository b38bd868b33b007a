// The hyperbaric (undrained) flow type: the rock dilates as it shears, its pore water cannot flow
// in fast enough, and the pore under-pressure that results presses the layer onto the intact rock
// and the tool. The under-pressure cannot exceed the absolute pressure of the water, at which it
// cavitates: with 10 m of water for the atmosphere,
//
//   dp <= p_atm + rho_w g z - p_vapour  ~  rho_w g (z + 10)
//
// Sources: Miedema (2014) chapter 9 ("Rock cutting: hyperbaric conditions"; the flow type with
// pore pressure forces W1 and W2 and cavitation); Zijsling (1987) "Single cutter testing - a key for
// PDC bit development", SPE 16529 (cutting forces rising with the borehole pressure); Kaitkay and
// Lei (2005) "Experimental study of rock cutting under external hydrostatic pressure", J. Mater.
// Process. Technol. 159:206-213; Alvarez Grima et al. (2015) "Effect of high hyperbaric pressure
// on rock cutting process", Eng. Geol. 196:24-36 (the analytical model: the flow type with the
// cavitation-bounded under-pressure).
//
// The force is the flow type's equilibrium with W1 = dp h / sin(beta) and W2 = dp h_b / sin(alpha)
// (merchant_flow_type.hpp), minimised over the shear angle beta numerically (Miedema 2014 ch. 9:
// the minimum no longer has a closed form once W2 is present). Without under-pressure (dp = 0,
// a dry or drained cut) it is Merchant's force; with h_b = 0 the under-pressure acts as extra
// cohesion dp tan(phi) (effective stress), the closed form with c + dp tan(phi).
//
// This is the undrained upper bound: the largest force the pore water can add at depth z. A cut
// slow enough for the water to follow (drained) gets Merchant's force.
#pragma once

#include "cutting_models/merchant_flow_type.hpp"

namespace rockcut::coupler::cutting_models {

/// The largest pore under-pressure before cavitation: p_atm + rho_w g z - p_vapour [Pa], never < 0.
double cavitation_under_pressure_pa(double water_depth_m, double water_density_kg_m3,
                                    double gravity_m_s2, double atmospheric_pressure_pa,
                                    double vapour_pressure_pa);

/// The flow type with pore under-pressure `under_pressure_pa` at its minimum-force shear angle.
FlowTypeForce hyperbaric_flow_type(double cohesion_pa, double friction_angle_deg,
                                   double tool_friction_angle_deg, double blade_angle_deg,
                                   double cut_depth_m, double blade_height_m,
                                   double under_pressure_pa);

}  // namespace rockcut::coupler::cutting_models
