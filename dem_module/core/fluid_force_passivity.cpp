#include "core/fluid_force_passivity.hpp"

#include <algorithm>

namespace rockcut::dem {

void FluidForcePassivity::exchange(std::span<const double> position, std::span<const double> held,
                                   std::span<const double> inv_mass, double dt,
                                   std::uint64_t step) {
  if (!on) return;
  const std::size_t n = inv_mass.size();
  const bool first = position_at_exchange.size() != 2 * n;
  // N = 1 (one step since the last exchange): the applied work is the trapezoid itself.
  const bool lagged = !first && step > exchange_step + 1;
  if (first) {
    work_j.assign(n, 0.0);
    speed2_dt.assign(n, 0.0);
    residual_j.assign(n, 0.0);
    coefficient.assign(n, 0.0);
    force.assign(2 * n, 0.0);
  }
  for (std::size_t i = 0; i < n; ++i) {
    double c = 0.0;
    if (lagged) {
      const double dx = position[2 * i] - position_at_exchange[2 * i];
      const double dy = position[2 * i + 1] - position_at_exchange[2 * i + 1];
      const double reference = 0.5 * ((force_at_exchange[2 * i] + held[2 * i]) * dx +
                                      (force_at_exchange[2 * i + 1] + held[2 * i + 1]) * dy);
      // Cumulative: what the dashpot took beyond the generation (its c is last interval's S)
      // is credited against the next, so over a run it takes out what the lag put in, no more.
      const double r = residual_j[i] + work_j[i] - reference;
      residual_j[i] = r;
      if (r > 0.0 && speed2_dt[i] > 0.0) {
        c = std::min(r / speed2_dt[i], 0.5 / (inv_mass[i] * dt));
      }
    }
    coefficient[i] = c;
    work_j[i] = 0.0;
    speed2_dt[i] = 0.0;
  }
  position_at_exchange.assign(position.begin(), position.end());
  force_at_exchange.assign(held.begin(), held.end());
  exchange_step = step;
}

}  // namespace rockcut::dem
