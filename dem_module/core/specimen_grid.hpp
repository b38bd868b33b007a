// Internal to the specimen generator: a uniform cell grid over disc centres (linked lists per cell,
// so insertion is O(1) and the grid can grow with the packing). Any two centres closer than one cell
// size lie in neighbouring cells (indices are clamped to the grid, which keeps that property for
// centres outside the bounds), so a 3 x 3 block of cells finds every candidate.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace rockcut::dem::detail {

class DiscGrid {
 public:
  DiscGrid(double x_lo, double y_lo, double x_hi, double y_hi, double cell_m)
      : x_lo_(x_lo), y_lo_(y_lo), inv_cell_(1.0 / cell_m) {
    nx_ = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((x_hi - x_lo) * inv_cell_)));
    ny_ = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((y_hi - y_lo) * inv_cell_)));
    head_.assign(static_cast<std::size_t>(nx_ * ny_), -1);
  }

  std::int64_t nx() const { return nx_; }
  std::int64_t ix(double x) const { return clamp_index((x - x_lo_) * inv_cell_, nx_); }
  std::int64_t iy(double y) const { return clamp_index((y - y_lo_) * inv_cell_, ny_); }

  /// Adds disc i (indices must be inserted as 0, 1, 2, ...).
  void insert(std::int32_t i, double x, double y) {
    const std::size_t c = static_cast<std::size_t>(iy(y) * nx_ + ix(x));
    next_.push_back(head_[c]);
    head_[c] = i;
  }

  /// Calls f(j) for every disc j in the 3 x 3 cells around (x, y); f returns false to stop early.
  template <class F>
  void for_each_near(double x, double y, F&& f) const {
    const std::int64_t cx = ix(x), cy = iy(y);
    for (std::int64_t jy = std::max<std::int64_t>(0, cy - 1); jy <= std::min(ny_ - 1, cy + 1); ++jy) {
      for (std::int64_t jx = std::max<std::int64_t>(0, cx - 1); jx <= std::min(nx_ - 1, cx + 1);
           ++jx) {
        for (std::int32_t j = head_[static_cast<std::size_t>(jy * nx_ + jx)]; j >= 0;
             j = next_[static_cast<std::size_t>(j)]) {
          if (!f(j)) return;
        }
      }
    }
  }

 private:
  static std::int64_t clamp_index(double u, std::int64_t n) {
    if (!(u > 0.0)) return 0;  // also NaN
    if (u >= static_cast<double>(n - 1)) return n - 1;
    return static_cast<std::int64_t>(u);
  }

  double x_lo_, y_lo_, inv_cell_;
  std::int64_t nx_ = 1, ny_ = 1;
  std::vector<std::int32_t> head_;
  std::vector<std::int32_t> next_;
};

}  // namespace rockcut::dem::detail
