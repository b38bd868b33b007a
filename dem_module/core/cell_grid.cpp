#include "core/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockcut::dem {

namespace {
// Caps the grid so that a few particles flung far away cannot make it huge.
constexpr long kMaxCells = 1L << 24;
}  // namespace

int CellGrid::cell_of(double x, double y) const {
  const int cx = std::clamp(static_cast<int>((x - x0_) * inv_size_), 0, nx_ - 1);
  const int cy = std::clamp(static_cast<int>((y - y0_) * inv_size_), 0, ny_ - 1);
  return cy * nx_ + cx;
}

void CellGrid::build(std::span<const double> position, double cell_size_m) {
  position_ = position;
  const std::size_t n = position.size() / 2;
  double xmin = std::numeric_limits<double>::max(), ymin = xmin;
  double xmax = std::numeric_limits<double>::lowest(), ymax = xmax;
  for (std::size_t i = 0; i < n; ++i) {
    xmin = std::min(xmin, position[2 * i]);
    xmax = std::max(xmax, position[2 * i]);
    ymin = std::min(ymin, position[2 * i + 1]);
    ymax = std::max(ymax, position[2 * i + 1]);
  }
  if (n == 0) xmin = xmax = ymin = ymax = 0;
  double size = cell_size_m;
  auto count = [&](double s) {
    return std::pair<long, long>(static_cast<long>((xmax - xmin) / s) + 1,
                                 static_cast<long>((ymax - ymin) / s) + 1);
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
