// The fluid's force between exchanges, extrapolated (Coupling.fluid_force "extrapolated"). With
// N DEM steps per fluid step the fluid's force F^m is known at the exchange times t_m only. Held
// constant (the paper's scheme for N = 1, "held"), it lags the grains by up to N dt, a negative
// damping of about k_f N dt / 2 for the pore fluid's stiffness k_f. Extrapolated on the line
// through the last two exchanges,
//   F(t) = F^m + (t - t_m) r,   r = (F^m - F^{m-1}) / (t_m - t_{m-1}),
// its error is second order in the fluid step, and what is left of the lag's work is third
// order (fluid_module/models/pore_pressure_model.hpp, kFluidExtrapolatedC). The DEM adds r dt to
// the held force in each drift, after the drift has booked the old force's half of the work, so
// the ledger's trapezoid sees the force each step's kick used. The rate starts at zero (the first
// exchange has no line), and an exchange replaces the extrapolated force with the fluid's.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace rockcut::dem {

struct FluidForceExtrapolation {
  bool on = false;
  std::vector<double> rate;        ///< r [N/(m s)], 2 per particle; empty while off
  std::vector<double> last_force;  ///< F^m [N/m], 2 per particle, the fluid's own; empty: none yet
  double last_time_s = 0.0;        ///< t_m

  /// Takes the fluid's force F at time t_s: the rate from the last one, then F as the last.
  void take(std::span<const double> force, double t_s) {
    if (!on) return;
    const std::size_t n = force.size();
    const double span_s = t_s - last_time_s;
    if (last_force.size() != n || !(span_s > 0.0)) {
      rate.assign(n, 0.0);
    } else {
      rate.resize(n);
      const double inv_span = 1.0 / span_s;
      for (std::size_t k = 0; k < n; ++k) rate[k] = (force[k] - last_force[k]) * inv_span;
    }
    last_force.assign(force.begin(), force.end());
    last_time_s = t_s;
  }
};

}  // namespace rockcut::dem
