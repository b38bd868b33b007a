#include "core/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockcut::dem {

namespace {
// Caps the grid so that a few particles flung far away cannot make it huge.
constexpr long kMaxCells = 1L << 24;
}  // namespace

// The cell index along one axis, clamped in floating point before the conversion: a coordinate
// far outside the grid, or not finite (a run about to trip the NaN guard), lands in an edge cell
// instead of overflowing the int.
static int axis_cell(double f, int cells) {
  if (f >= static_cast<double>(cells)) return cells - 1;
  return f >= 0.0 ? static_cast<int>(f) : 0;  // NaN compares false: cell 0
}

int CellGrid::cell_of(double x, double y) const {
  return axis_cell((y - y0_) * inv_size_, ny_) * nx_ + axis_cell((x - x0_) * inv_size_, nx_);
}

void CellGrid::build(std::span<const double> position, double cell_size_m) {
  position_ = position;
  const std::size_t n = position.size() / 2;
  double xmin = std::numeric_limits<double>::max(), ymin = xmin;
  double xmax = std::numeric_limits<double>::lowest(), ymax = xmax;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = position[2 * i], y = position[2 * i + 1];
    if (!std::isfinite(x) || !std::isfinite(y)) continue;  // binned at an edge (cell_of)
    xmin = std::min(xmin, x);
    xmax = std::max(xmax, x);
    ymin = std::min(ymin, y);
    ymax = std::max(ymax, y);
  }
  if (xmin > xmax) xmin = xmax = ymin = ymax = 0;  // no particle, or none finite
  double size = cell_size_m;
  // In doubles: extents of discs flung very far must not overflow an integer on the way.
  const double ex = std::min(xmax - xmin, 1e300), ey = std::min(ymax - ymin, 1e300);
  auto count = [&](double s) {
    return std::pair<double, double>(std::floor(ex / s) + 1, std::floor(ey / s) + 1);
  };
  while (count(size).first * count(size).second > kMaxCells) size *= 2;  // never smaller: pairs stay found
  x0_ = xmin;
  y0_ = ymin;
  inv_size_ = 1.0 / size;
  nx_ = static_cast<int>(count(size).first);
  ny_ = static_cast<int>(count(size).second);

  const std::size_t cells = static_cast<std::size_t>(nx_) * ny_;
  start_.assign(cells + 1, 0);
  cell_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    cell_[i] = cell_of(position[2 * i], position[2 * i + 1]);
    ++start_[cell_[i] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  sorted_.resize(n);
  std::vector<std::uint32_t>& fill = sorted_;
  // Counting sort; `start_` is restored afterwards.
  for (std::size_t i = 0; i < n; ++i) fill[start_[cell_[i]]++] = static_cast<std::uint32_t>(i);
  for (std::size_t c = cells; c > 0; --c) start_[c] = start_[c - 1];
  start_[0] = 0;
}

}  // namespace rockcut::dem
