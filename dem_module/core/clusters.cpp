#include "core/clusters.hpp"

#include <algorithm>
#include <numbers>
#include <numeric>

namespace rockcut::dem {

namespace {
std::uint32_t root(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];  // path halving
    i = parent[i];
  }
  return i;
}
}  // namespace

ChipStats chip_stats(const Particles& p, const BondSet& bonds) {
  const std::size_t n = p.size();
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    const std::uint32_t a = root(parent, bonds.first(k)), b = root(parent, bonds.second(k));
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  std::vector<std::uint32_t> size(n, 0);
  std::vector<double> area(n, 0.0);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t r = root(parent, i);
    ++size[r];
    area[r] += std::numbers::pi * p.radius[i] * p.radius[i];
  }
  ChipStats s;
  std::uint32_t largest = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (size[i] > size[largest]) largest = i;
  }
  double total = 0.0;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (size[i] < 2 || i == largest) continue;
    ++s.chips;
    total += area[i];
  }
  s.mean_area_m2 = s.chips ? total / s.chips : 0.0;
  return s;
}

}  // namespace rockcut::dem
