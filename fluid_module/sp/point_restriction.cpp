#include "sp/point_restriction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sp/kernel.hpp"

namespace rockcut::fluid::sp {

namespace {

/// The grains binned into square cells of side `cell_m` (one pass, built once).
struct CellGrid {
  CellGrid(std::span<const double> position, double cell_m) : cell(cell_m) {
    const std::size_t n = position.size() / 2;
    double xmax = -std::numeric_limits<double>::infinity(), ymax = xmax;
    x0 = y0 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      x0 = std::min(x0, position[2 * i]);
      y0 = std::min(y0, position[2 * i + 1]);
      xmax = std::max(xmax, position[2 * i]);
      ymax = std::max(ymax, position[2 * i + 1]);
    }
    if (n == 0 || !std::isfinite(x0 + y0 + xmax + ymax)) {
      throw std::invalid_argument("fluid points: the initial positions are empty or not finite");
    }
    x1 = xmax;
    y1 = ymax;
    nx = static_cast<int>((xmax - x0) / cell) + 1;
    ny = static_cast<int>((ymax - y0) / cell) + 1;
    start.assign(static_cast<std::size_t>(nx) * ny + 1, 0);
    of.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      of[i] = index(position[2 * i], position[2 * i + 1]);
      ++start[of[i] + 1];
    }
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    members.resize(n);
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) members[fill[of[i]]++] = static_cast<int>(i);
  }
  std::size_t index(double x, double y) const {
    const int cx = std::min(nx - 1, static_cast<int>((x - x0) / cell));
    const int cy = std::min(ny - 1, static_cast<int>((y - y0) / cell));
    return static_cast<std::size_t>(cy) * nx + cx;
  }
  /// Calls visit(j) for every grain in the 3 x 3 cells around cell c.
  template <class Visit>
  void around(std::size_t c, Visit&& visit) const {
    const int cx = static_cast<int>(c % nx), cy = static_cast<int>(c / nx);
    for (int y = std::max(0, cy - 1); y <= std::min(ny - 1, cy + 1); ++y) {
      for (int x = std::max(0, cx - 1); x <= std::min(nx - 1, cx + 1); ++x) {
        const std::size_t k = static_cast<std::size_t>(y) * nx + x;
        for (std::size_t m = start[k]; m < start[k + 1]; ++m) visit(members[m]);
      }
    }
  }
  double cell, x0, y0, x1 = 0, y1 = 0;  // the bounding box
  int nx = 0, ny = 0;
  std::vector<std::size_t> start, of;
  std::vector<int> members;
};

}  // namespace

PointRestriction::PointRestriction(std::span<const double> position, double spacing_m,
                                   double support_m)
    : spacing_m_(spacing_m), support_m_(support_m) {
  if (!(spacing_m > 0.0) || !(support_m >= spacing_m)) {
    throw std::invalid_argument("fluid points: the points' spacing (" + std::to_string(spacing_m) +
                                " m) must be positive and the weights' support (" +
                                std::to_string(support_m) + " m) at least as large");
  }
  const std::size_t n = position.size() / 2;
  const CellGrid grid(position, support_m);

  // The points: the grain nearest each node of a lattice over the packing's bounding box, its
  // spacing the nearest to spacing_m that puts nodes on all four sides (where the pore fluid
  // drains or is sealed), one point per grain.
  std::vector<char> chosen(n, 0);
  const auto intervals = [&](double length) {
    return length > 0.0 ? std::max<long>(1, std::lround(length / spacing_m)) : 0L;
  };
  const long nx = intervals(grid.x1 - grid.x0), ny = intervals(grid.y1 - grid.y0);
  const double dx = nx ? (grid.x1 - grid.x0) / static_cast<double>(nx) : 0.0;
  const double dy = ny ? (grid.y1 - grid.y0) / static_cast<double>(ny) : 0.0;
  for (long iy = 0; iy <= ny; ++iy) {
    for (long ix = 0; ix <= nx; ++ix) {
      const double x = grid.x0 + static_cast<double>(ix) * dx;
      const double y = grid.y0 + static_cast<double>(iy) * dy;
      int nearest = -1;
      double best = 0.25 * spacing_m * spacing_m;  // none within half a spacing: a hole
      grid.around(grid.index(x, y), [&](int j) {
        const double ex = position[2 * j] - x, ey = position[2 * j + 1] - y;
        const double d2 = ex * ex + ey * ey;
        if (d2 < best || (d2 == best && j < nearest)) {
          best = d2;
          nearest = j;
        }
      });
      if (nearest >= 0 && !chosen[nearest]) {
        chosen[nearest] = 1;
        point_grain_.push_back(nearest);
      }
    }
  }
  // A grain that no point reaches (beside a hole or a ragged outline) becomes a point itself.
  const double reach2 = support_m * support_m;
  for (std::size_t i = 0; i < n; ++i) {
    bool reached = false;
    grid.around(grid.of[i], [&](int j) {
      if (!chosen[j] || reached) return;
      const double ex = position[2 * j] - position[2 * i];
      const double ey = position[2 * j + 1] - position[2 * i + 1];
      reached = ex * ex + ey * ey < reach2;
    });
    if (!reached) {
      chosen[i] = 1;
      point_grain_.push_back(static_cast<int>(i));
    }
  }
  std::sort(point_grain_.begin(), point_grain_.end());  // in the grains' (spatial) order

  // Each point's weights over the grains within the support, in grain order.
  const WendlandC2 kernel(support_m);
  row_start_.assign(1, 0);
  std::vector<int> row;
  for (const int g : point_grain_) {
    row.clear();
    grid.around(grid.of[g], [&](int j) { row.push_back(j); });
    std::sort(row.begin(), row.end());
    const std::size_t first = row_grain_.size();
    for (const int j : row) {
      const double dx = position[2 * j] - position[2 * g];
      const double dy = position[2 * j + 1] - position[2 * g + 1];
      const double w = kernel.w(std::sqrt(dx * dx + dy * dy));
      if (!(w > 0.0)) continue;
      row_grain_.push_back(j);
      row_weight_.push_back(w);
    }
    centre_weights(position, g, first);
    row_start_.push_back(row_grain_.size());
  }

  // The transpose, each column in point order.
  column_start_.assign(n + 1, 0);
  for (const int j : row_grain_) ++column_start_[j + 1];
  for (std::size_t j = 1; j <= n; ++j) column_start_[j] += column_start_[j - 1];
  column_point_.resize(row_grain_.size());
  column_weight_.resize(row_grain_.size());
  std::vector<std::size_t> fill(column_start_.begin(), column_start_.end() - 1);
  for (std::size_t p = 0; p < points(); ++p) {
    for (std::size_t m = row_start_[p]; m < row_start_[p + 1]; ++m) {
      const std::size_t at = fill[row_grain_[m]]++;
      column_point_[at] = static_cast<int>(p);
      column_weight_[at] = row_weight_[m];
    }
  }
  column_sum_.assign(n, 0.0);
  main_point_.assign(n, -1);
  for (std::size_t j = 0; j < n; ++j) {
    double best = 0.0;
    for (std::size_t m = column_start_[j]; m < column_start_[j + 1]; ++m) {
      column_sum_[j] += column_weight_[m];
      if (column_weight_[m] > best) {
        best = column_weight_[m];
        main_point_[j] = column_point_[m];
      }
    }
  }
}

void PointRestriction::centre_weights(std::span<const double> position, int g,
                                      std::size_t first) {
  // Maximum entropy with the kernel as prior (Arroyo and Ortiz 2006): R_pj proportional to
  // W_j exp(lambda . d_j), d_j = (x_j - x_g) / support, with lambda the minimiser of the convex
  // log sum_j W_j exp(lambda . d_j), whose gradient is sum_j R_pj d_j. Newton's method with a
  // halving step; at a corner of the packing, where the host is on the hull of its grains, the
  // minimum lies at infinity and the weights gather on the grains level with it: the iteration
  // stops at |lambda| = kMaxTilt with the residual of that point.
  constexpr double kMaxTilt = 1e4;
  const std::size_t end = row_weight_.size();
  const double inv = 1.0 / support_m_;
  std::vector<double>& prior = scratch_;
  prior.assign(row_weight_.begin() + static_cast<std::ptrdiff_t>(first), row_weight_.end());
  auto evaluate = [&](double lx, double ly, double& log_z, double& gx, double& gy, double& hxx,
                      double& hxy, double& hyy) {
    double z = 0.0, shift = 0.0;  // exp(lambda . d - shift) with shift its largest exponent
    for (std::size_t m = first; m < end; ++m) {
      const double dx = (position[2 * row_grain_[m]] - position[2 * g]) * inv;
      const double dy = (position[2 * row_grain_[m] + 1] - position[2 * g + 1]) * inv;
      shift = std::max(shift, lx * dx + ly * dy);
    }
    gx = gy = hxx = hxy = hyy = 0.0;
    for (std::size_t m = first; m < end; ++m) {
      const double dx = (position[2 * row_grain_[m]] - position[2 * g]) * inv;
      const double dy = (position[2 * row_grain_[m] + 1] - position[2 * g + 1]) * inv;
      const double w = prior[m - first] * std::exp(lx * dx + ly * dy - shift);
      row_weight_[m] = w;
      z += w;
      gx += w * dx;
      gy += w * dy;
      hxx += w * dx * dx;
      hxy += w * dx * dy;
      hyy += w * dy * dy;
    }
    gx /= z;
    gy /= z;
    hxx = hxx / z - gx * gx;
    hxy = hxy / z - gx * gy;
    hyy = hyy / z - gy * gy;
    log_z = std::log(z) + shift;
    for (std::size_t m = first; m < end; ++m) row_weight_[m] /= z;
  };
  double lx = 0.0, ly = 0.0, f, gx, gy, hxx, hxy, hyy;
  evaluate(lx, ly, f, gx, gy, hxx, hxy, hyy);
  for (int it = 0; it < 200 && std::hypot(gx, gy) > 1e-12; ++it) {
    const double det = hxx * hyy - hxy * hxy;
    double sx = -gx, sy = -gy;  // steepest descent where the covariance is singular
    if (det > 1e-14 * (hxx + hyy) * (hxx + hyy)) {
      sx = -(hyy * gx - hxy * gy) / det;
      sy = -(hxx * gy - hxy * gx) / det;
    }
    double step = 1.0, f_new = f, ngx, ngy, nxx, nxy, nyy;
    for (int k = 0; k < 40; ++k, step *= 0.5) {
      evaluate(lx + step * sx, ly + step * sy, f_new, ngx, ngy, nxx, nxy, nyy);
      if (f_new <= f) break;
    }
    if (!(f_new <= f)) {
      evaluate(lx, ly, f, gx, gy, hxx, hxy, hyy);  // no descent left: keep the last weights
      break;
    }
    lx += step * sx;
    ly += step * sy;
    f = f_new;
    gx = ngx, gy = ngy, hxx = nxx, hxy = nxy, hyy = nyy;
    if (std::hypot(lx, ly) > kMaxTilt) break;
  }
}

void PointRestriction::restrict_to_points(std::span<const double> grain, std::span<double> point,
                                          int components) const {
  const auto count = static_cast<std::ptrdiff_t>(points());
  const double* in = grain.data();
  double* out = point.data();
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t p = 0; p < count; ++p) {
    for (int c = 0; c < components; ++c) {
      double sum = 0.0;
      for (std::size_t m = row_start_[p]; m < row_start_[p + 1]; ++m) {
        sum += row_weight_[m] * in[components * row_grain_[m] + c];
      }
      out[components * p + c] = sum;
    }
  }
}

void PointRestriction::spread_to_grains(std::span<const double> point, std::span<double> grain,
                                        int components) const {
  const auto count = static_cast<std::ptrdiff_t>(grains());
  const double* in = point.data();
  double* out = grain.data();
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t j = 0; j < count; ++j) {
    for (int c = 0; c < components; ++c) {
      double sum = 0.0;
      for (std::size_t m = column_start_[j]; m < column_start_[j + 1]; ++m) {
        sum += column_weight_[m] * in[components * column_point_[m] + c];
      }
      out[components * j + c] = sum;
    }
  }
}

void PointRestriction::interpolate_to_grains(std::span<const double> point,
                                             std::span<double> grain) const {
  spread_to_grains(point, grain, 1);
  for (std::size_t j = 0; j < grains(); ++j) {
    if (column_sum_[j] > 0.0) grain[j] /= column_sum_[j];
  }
}

}  // namespace rockcut::fluid::sp
