#include "sp/point_restriction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rockcut::fluid::sp {

namespace {

void check_components(int components) {
  if (components != 1 && components != 2) {
    throw std::invalid_argument("fluid points: " + std::to_string(components) +
                                " values per particle; 1 or 2 are restricted");
  }
}

}  // namespace

PointRestriction::PointRestriction(std::span<const double> position,
                                   std::span<const double> radius, double spacing_grains) {
  const std::size_t n = radius.size();
  if (!(spacing_grains > 0.0) || position.size() != 2 * n || n == 0) {
    throw std::invalid_argument("fluid points: a spacing of " + std::to_string(spacing_grains) +
                                " grain spacings over " + std::to_string(n) + " grains");
  }
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (std::size_t i = 0; i < n; ++i) {
    x0 = std::min(x0, position[2 * i]);
    x1 = std::max(x1, position[2 * i]);
    y0 = std::min(y0, position[2 * i + 1]);
    y1 = std::max(y1, position[2 * i + 1]);
  }
  if (!std::isfinite(x0 + x1 + y0 + y1)) {
    throw std::invalid_argument("fluid points: an initial position is not finite");
  }
  // The grains' mean spacing, sqrt(area / grains) over their bounding box.
  const double grain_spacing_m = std::sqrt((x1 - x0) * (y1 - y0) / static_cast<double>(n));
  if (!(grain_spacing_m > 0.0)) {
    throw std::invalid_argument("fluid.point_spacing needs grains spread over an area");
  }
  const double spacing_m = spacing_grains * grain_spacing_m;
  // The clusters: each grain joins the nearest node of a lattice whose spacing is the nearest to
  // spacing_m that puts nodes on all four sides; the nodes without grains hold no point.
  const auto intervals = [&](double length) {
    return length > 0.0 ? std::max<long>(1, std::lround(length / spacing_m)) : 0L;
  };
  const long nx = intervals(x1 - x0), ny = intervals(y1 - y0);
  const double dx = nx ? (x1 - x0) / static_cast<double>(nx) : 1.0;
  const double dy = ny ? (y1 - y0) / static_cast<double>(ny) : 1.0;
  node_spacing_m_[0] = dx;
  node_spacing_m_[1] = dy;
  std::vector<int> point_of_node(static_cast<std::size_t>((nx + 1) * (ny + 1)), -1);
  point_of_.resize(n);  // first each grain's node, then that node's point
  for (std::size_t i = 0; i < n; ++i) {
    const long ix = std::clamp(std::lround((position[2 * i] - x0) / dx), 0L, nx);
    const long iy = std::clamp(std::lround((position[2 * i + 1] - y0) / dy), 0L, ny);
    point_of_[i] = static_cast<int>(iy * (nx + 1) + ix);
    point_of_node[static_cast<std::size_t>(point_of_[i])] = 0;
  }
  std::size_t m = 0;  // the points in the nodes' order, row by row
  for (int& p : point_of_node) {
    if (p == 0) p = static_cast<int>(m++);
  }
  for (int& p : point_of_) p = point_of_node[static_cast<std::size_t>(p)];

  // The clusters in grain order and their weights a_j / A_p.
  cluster_start_.assign(m + 1, 0);
  for (int p : point_of_) ++cluster_start_[static_cast<std::size_t>(p) + 1];
  for (std::size_t p = 1; p <= m; ++p) cluster_start_[p] += cluster_start_[p - 1];
  cluster_.resize(n);
  std::vector<std::size_t> fill(cluster_start_.begin(), cluster_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) cluster_[fill[point_of_[i]]++] = static_cast<int>(i);
  area_m2_.assign(m, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    area_m2_[point_of_[i]] += std::numbers::pi * radius[i] * radius[i];
  }
  weight_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    weight_[i] = std::numbers::pi * radius[i] * radius[i] / area_m2_[point_of_[i]];
  }
}

void PointRestriction::restrict_to_points(std::span<const double> grain, std::span<double> point,
                                          int components) const {
  check_components(components);
  const auto count = static_cast<std::ptrdiff_t>(points());
  const double* in = grain.data();
  double* out = point.data();
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t p = 0; p < count; ++p) {
    double sum[2] = {0.0, 0.0};
    for (std::size_t k = cluster_start_[p]; k < cluster_start_[p + 1]; ++k) {
      const std::size_t j = static_cast<std::size_t>(cluster_[k]);
      for (int c = 0; c < components; ++c) sum[c] += weight_[j] * in[components * j + c];
    }
    for (int c = 0; c < components; ++c) out[components * p + c] = sum[c];
  }
}

void PointRestriction::spread_to_grains(std::span<const double> point, std::span<double> grain,
                                        int components) const {
  check_components(components);
  const auto count = static_cast<std::ptrdiff_t>(grains());
  const double* in = point.data();
  double* out = grain.data();
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t j = 0; j < count; ++j) {
    const std::ptrdiff_t p = point_of_[j];
    for (int c = 0; c < components; ++c) {
      out[components * j + c] = weight_[j] * in[components * p + c];
    }
  }
}

void PointRestriction::show_on_grains(std::span<const double> point,
                                      std::span<double> grain) const {
  for (std::size_t j = 0; j < grains(); ++j) grain[j] = point[point_of_[j]];
}

}  // namespace rockcut::fluid::sp
