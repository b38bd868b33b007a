#include "sp/boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockcut::fluid::sp {

void Sides::fit(std::span<const double> position) {
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin, xmax = -xmin, ymax = -xmin;
  for (std::size_t k = 0; k + 1 < position.size(); k += 2) {
    xmin = std::min(xmin, position[k]);
    xmax = std::max(xmax, position[k]);
    ymin = std::min(ymin, position[k + 1]);
    ymax = std::max(ymax, position[k + 1]);
  }
  at_m = {xmin, xmax, ymin, ymax};
}

BoundaryCounts classify_boundary(std::span<const double> div_r, double surface_div_r,
                                 std::span<const double> position, std::span<const double> radius,
                                 const Sides& sides, std::span<Boundary> out) {
  BoundaryCounts counts;
  const bool any_open = sides.any_open();
  for (std::size_t i = 0; i < div_r.size(); ++i) {
    if (div_r[i] > surface_div_r) {
      out[i] = Boundary::interior;
      continue;
    }
    const double x = position[2 * i], y = position[2 * i + 1], d = radius[i];
    const std::array<double, 4> distance = {std::abs(x - sides.at_m[Sides::left]),
                                            std::abs(x - sides.at_m[Sides::right]),
                                            std::abs(y - sides.at_m[Sides::bottom]),
                                            std::abs(y - sides.at_m[Sides::top])};
    bool near_sealed = false, near_open = false;
    for (int s = 0; s < 4; ++s) {
      if (distance[s] < d) (sides.sealed[s] ? near_sealed : near_open) = true;
    }
    const bool drained = near_open || (!near_sealed && any_open);
    out[i] = drained ? Boundary::drained : Boundary::sealed;
    ++(drained ? counts.drained : counts.sealed);
  }
  return counts;
}

}  // namespace rockcut::fluid::sp
