#include "core/membrane_load.hpp"

#include <algorithm>
#include <cmath>

namespace rockcut::dem {

MembraneLoad membrane_load(const Particles& p, double stress_pa) {
  MembraneLoad m;
  m.stress_pa = stress_pa;
  if (p.size() == 0) return m;
  double bottom = 1e300, top = -1e300, r_max = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    bottom = std::min(bottom, p.position[2 * i + 1] - p.radius[i]);
    top = std::max(top, p.position[2 * i + 1] + p.radius[i]);
    r_max = std::max(r_max, p.radius[i]);
  }
  m.height_m = top - bottom;
  const auto bands = static_cast<std::size_t>(std::max(1.0, std::ceil(m.height_m / (2 * r_max))));
  const double band_m = m.height_m / static_cast<double>(bands);
  // Per band: the disc reaching furthest left (smallest x - r) and furthest right (largest x + r).
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> left(bands, kNone), right(bands, kNone);
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    const double x = p.position[2 * i], r = p.radius[i];
    const auto b = std::min(bands - 1, static_cast<std::size_t>(
                                           (p.position[2 * i + 1] - bottom) / band_m));
    if (left[b] == kNone || x - r < p.position[2 * left[b]] - p.radius[left[b]]) left[b] = i;
    if (right[b] == kNone || x + r > p.position[2 * right[b]] + p.radius[right[b]]) right[b] = i;
  }
  // A band without a disc (a hole in the packing) is skipped: the bands that hold discs, n of
  // them, share the line load sigma_c H, sigma_c H / n each.
  std::size_t loaded = 0;
  for (std::size_t b = 0; b < bands; ++b) loaded += left[b] != kNone;
  const double share = stress_pa * m.height_m / static_cast<double>(std::max<std::size_t>(loaded, 1));
  for (std::size_t b = 0; b < bands; ++b) {
    if (left[b] == kNone) continue;
    m.particles.push_back(left[b]);
    m.force_x_n_per_m.push_back(share);
  }
  for (std::size_t b = 0; b < bands; ++b) {
    if (right[b] == kNone) continue;
    m.particles.push_back(right[b]);
    m.force_x_n_per_m.push_back(-share);
  }
  return m;
}

}  // namespace rockcut::dem
