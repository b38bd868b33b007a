// packing_stats: packing fraction, coordination and overlap of a disc packing (see
// specimen_generator.hpp). All pairs closer than the contact distance are found with a cell grid.
#include "core/specimen_generator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/specimen_grid.hpp"

namespace rockcut::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;

double region_area(const PackingRegion& g) {
  return g.shape == PackingRegion::Shape::circle ? kPi * g.radius_m * g.radius_m
                                                 : g.width_m * g.height_m;
}

}  // namespace

PackingStats packing_stats(const Packing& p, const PackingRegion& region, double gap_tolerance_m) {
  if (!std::isfinite(gap_tolerance_m)) {
    throw std::invalid_argument("packing_stats: gap_tolerance_m must be finite");
  }
  const double area = region_area(region);
  if (!(area > 0.0) || !std::isfinite(area)) {
    throw std::invalid_argument("packing_stats: region area must be positive");
  }
  const std::size_t n = p.radius_m.size();
  if (p.x_m.size() != n || p.y_m.size() != n) {
    throw std::invalid_argument("packing_stats: x_m, y_m and radius_m differ in size");
  }
  PackingStats s;
  double solid = 0.0;
  for (double r : p.radius_m) solid += kPi * r * r;
  s.packing_fraction = solid / area;
  s.porosity = 1.0 - s.packing_fraction;
  if (n == 0) return s;

  const double rmax = *std::max_element(p.radius_m.begin(), p.radius_m.end());
  const auto [xmin, xmax] = std::minmax_element(p.x_m.begin(), p.x_m.end());
  const auto [ymin, ymax] = std::minmax_element(p.y_m.begin(), p.y_m.end());
  // Cells of at least the largest contact distance; coarser if that would need over ~1.6e7 cells.
  const double spread = std::max(*xmax - *xmin, *ymax - *ymin);
  const double cell = std::max({2.0 * rmax + std::max(gap_tolerance_m, 0.0), spread / 4096.0, 1e-300});
  detail::DiscGrid grid(*xmin, *ymin, *xmax, *ymax, cell);
  for (std::size_t i = 0; i < n; ++i) grid.insert(static_cast<std::int32_t>(i), p.x_m[i], p.y_m[i]);

  double min_gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    grid.for_each_near(p.x_m[i], p.y_m[i], [&](std::int32_t jj) {
      const auto j = static_cast<std::size_t>(jj);
      if (j <= i) return true;
      const double dx = p.x_m[j] - p.x_m[i], dy = p.y_m[j] - p.y_m[i];
      const double gap = std::sqrt(dx * dx + dy * dy) - p.radius_m[i] - p.radius_m[j];
      min_gap = std::min(min_gap, gap);
      if (gap <= gap_tolerance_m) ++s.touching_pairs;
      return true;
    });
  }
  s.max_overlap_m = std::max(0.0, -min_gap);
  s.mean_coordination = 2.0 * static_cast<double>(s.touching_pairs) / static_cast<double>(n);
  return s;
}

}  // namespace rockcut::dem
