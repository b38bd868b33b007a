// The coupling lag's energy taken out again (Coupling.lag_correction "passivity"): a passivity
// observer and controller per grain (Hannaford & Ryu 2002; for co-simulation the same energy
// residual as Sadjina et al. 2017's NEPCE).
//
// The fluid's force is the gradient of its stored energy (the adjoint form,
// fluid_module/sp/adjoint_pressure_force.cpp), so over a fluid step from x^m to x^{m+1} the work
// its pressures can do on grain i is the trapezoid
//   W_ref,i = (F^m_i + F^{m+1}_i) / 2 . (x^{m+1}_i - x^m_i)
// (exact for an undrained, quadratic stored energy on the operators of the step; the flow's
// dissipation is in it). Between exchanges the DEM applies the held or the extrapolated force,
// whose work W_i differs from W_ref,i by what the lag generated: held, on a spring k_f, about
// k_f |x^{m+1} - x^m|^2 (N - 1) / (2N) an interval, never negative. The observer keeps per grain
// the energy the interface generated and the dashpot has not yet taken out,
//   R_i <- R_i + W_i - W_ref,i                                 (W_i includes the dashpot's work),
// and the controller takes it out over the next interval with a dashpot on that grain's velocity,
//   F_c,i = -c_i v_i,   c_i = max(R_i, 0) / S_i,   S_i = sum over the last interval of |v_i|^2 dt,
// at most m_i / (2 dt) (an explicit dashpot that never reverses a velocity). What it leaves stays
// in R_i; what it takes beyond (S_i grew) is credited, R_i < 0, against the next generation, so
// over a run it takes out what the lag put in and no more (the observer of Hannaford & Ryu is
// cumulative too). At N = 1 there is nothing between exchanges and the controller stays off; it
// takes out only energy the interface generated, never the fluid's own (W_ref is what the fluid
// gave).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rockcut::dem {

struct FluidForcePassivity {
  bool on = false;
  std::vector<double> position_at_exchange;  ///< x^m [m], 2 per particle; empty: no exchange yet
  std::vector<double> force_at_exchange;     ///< F^m [N/m], 2 per particle, as held
  std::vector<double> work_j;                ///< W_i since x^m [J/m], fluid force and dashpot
  std::vector<double> speed2_dt;             ///< S_i since x^m [m^2/s]
  std::vector<double> residual_j;            ///< R_i [J/m]
  std::vector<double> coefficient;           ///< c_i [N s/m^2] of this interval
  /// F_c [N/m] of the last evaluation, 2 per particle: its work is booked as the trapezoid over
  /// the two drifts it kicks. Booked one-sided instead (c |v|^2 dt), the observer counts up to a
  /// quarter more taken out than was at the clip, and the corrected spring gains 1.8 % in twenty
  /// periods (tests/dem/fluid_force_passivity_test.cpp).
  std::vector<double> force;
  std::uint64_t exchange_step = 0;  ///< the DEM step of x^m

  /// The DEM's exchange at `step` with the new held force F^{m+1} (`held`) and positions x^{m+1}:
  /// updates R and sets c for the next interval of steps of dt.
  void exchange(std::span<const double> position, std::span<const double> held,
                std::span<const double> inv_mass, double dt, std::uint64_t step);
  bool active() const { return on && !coefficient.empty(); }
};

}  // namespace rockcut::dem
