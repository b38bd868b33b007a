// Each grain's own pore-fluid stiffness between exchanges (Coupling.fluid_stiffness "self";
// docs/model.md, "The grain's own fluid stiffness between exchanges"). Undrained over a fluid
// step, the pore fluid answers a grain's displacement u_i with the force -K_ii u_i, where
// K_ii = alpha M [A_i C_i C_i^T + sum_j A_j B_ji B_ji^T] is the grain's own block of the
// undrained stiffness (fluid_module/sp/self_stiffness.cpp). Held or extrapolated, the fluid's
// force lags that answer by up to N dt, a negative damping K N dt / 2 (or its third-order rest):
// the lag's instability is the grain's own stiffness seen late. Applied by the DEM at each step,
//   F(t) = F_held(t) - K_ii (x_i(t) - x_i^m),
// the grain's own answer has no lag; only its neighbours' motion is still seen at the exchange.
// The DEM adds -K_ii v dt to the force in each drift, after the drift has booked the old force's
// half of the work (as the extrapolation's r dt), so the ledger's trapezoid sees the force each
// kick used. With the extrapolation on, the fluid's own force already holds the self answer to
// the last interval's motion, F^m - F^{m-1} ~ -K (x^m - x^{m-1}) + ..., so the rate drops it:
//   r' = r + K_ii (x^m - x^{m-1}) / (t_m - t_{m-1}),
// or the self answer would be counted twice. At N = 1 every step ends at an exchange that
// replaces the force, and nothing of this is used.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockcut::dem {

struct FluidSelfStiffness {
  bool on = false;
  std::vector<double> k_pa;           ///< K_ii [Pa] (xx, xy, yy) per grain; empty: none yet
  std::vector<double> last_position;  ///< x^m [m], 2 per grain, at the last exchange
  double last_time_s = 0.0;           ///< t_m

  /// Takes the exchange at t_s: drops the self answer to the last interval's motion (under the
  /// old K) from the extrapolation's `rate` (empty: the force is held), then holds `k` (3 per
  /// grain) for the next interval. Checks the size first: a refused array changes nothing.
  void take(std::span<const double> k, std::span<const double> position, double t_s,
            std::vector<double>& rate) {
    if (!on) return;
    const std::size_t n = position.size() / 2;
    if (k.size() != 3 * n) {
      throw std::invalid_argument("fluid self stiffness has " + std::to_string(k.size()) +
                                  " values for " + std::to_string(n) + " particles (3 each)");
    }
    const double span_s = t_s - last_time_s;
    if (rate.size() == 2 * n && k_pa.size() == 3 * n && last_position.size() == 2 * n &&
        span_s > 0.0) {
      const double inv_span = 1.0 / span_s;
      for (std::size_t i = 0; i < n; ++i) {
        const double ux = position[2 * i] - last_position[2 * i];
        const double uy = position[2 * i + 1] - last_position[2 * i + 1];
        rate[2 * i] += (k_pa[3 * i] * ux + k_pa[3 * i + 1] * uy) * inv_span;
        rate[2 * i + 1] += (k_pa[3 * i + 1] * ux + k_pa[3 * i + 2] * uy) * inv_span;
      }
    }
    k_pa.assign(k.begin(), k.end());
    last_position.assign(position.begin(), position.end());
    last_time_s = t_s;
  }
  /// Whether the held K_ii moves any grain's force (then its work must be booked even where the
  /// fluid's force at the exchange is zero).
  bool stiffens() const {
    return std::any_of(k_pa.begin(), k_pa.end(), [](double k) { return k != 0.0; });
  }
};

}  // namespace rockcut::dem
