#include "sp/boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sp/surface_detection.hpp"

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

namespace {

/// Whether the particle at (x, y) with outward normal (nx, ny) / norm faces a rigid segment
/// closer than h_m to its centre.
bool faces_segment(double x, double y, double nx, double ny, double norm, double h_m,
                   std::span<const double> segments, double facing_cosine) {
  if (norm <= 0.0) return false;
  for (std::size_t k = 0; k + 3 < segments.size(); k += 4) {
    const double ax = segments[k], ay = segments[k + 1];
    const double ex = segments[k + 2] - ax, ey = segments[k + 3] - ay;
    const double len2 = ex * ex + ey * ey;
    const double t = len2 > 0.0 ? std::clamp(((x - ax) * ex + (y - ay) * ey) / len2, 0.0, 1.0) : 0.0;
    const double dx = ax + t * ex - x, dy = ay + t * ey - y;
    const double d = std::hypot(dx, dy);
    if (d >= h_m || d <= 0.0) continue;
    if ((nx * dx + ny * dy) / (norm * d) > facing_cosine) return true;
  }
  return false;
}

}  // namespace

BoundaryCounts classify_boundary(std::span<const double> div_r, std::span<const double> normal,
                                 double surface_div_r, double h_m,
                                 std::span<const double> position, std::span<const double> radius,
                                 const Sides& sides, std::span<Boundary> out,
                                 std::span<const double> segments) {
  // Outward normals of the sides (left, right, bottom, top).
  static constexpr double kSideNormal[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
  static constexpr double kFacing = 0.5;  // cos 60 degrees
  BoundaryCounts counts;
  const bool any_open = sides.any_open();
  for (std::size_t i = 0; i < div_r.size(); ++i) {
    if (inside_body(div_r[i], surface_div_r)) {
      out[i] = Boundary::interior;
      continue;
    }
    const double x = position[2 * i], y = position[2 * i + 1];
    const std::array<double, 4> distance = {
        std::abs(x - sides.at_m[Sides::left]), std::abs(x - sides.at_m[Sides::right]),
        std::abs(y - sides.at_m[Sides::bottom]), std::abs(y - sides.at_m[Sides::top])};
    const double nx = normal[2 * i], ny = normal[2 * i + 1];
    const double norm = std::hypot(nx, ny);
    if (!segments.empty() && faces_segment(x, y, nx, ny, norm, h_m, segments, kFacing)) {
      out[i] = Boundary::sealed;
      ++counts.sealed;
      continue;
    }
    bool faces_sealed = false, faces_open = false;
    for (int s = 0; s < 4; ++s) {
      const double cosine = norm > 0.0 ? (nx * kSideNormal[s][0] + ny * kSideNormal[s][1]) / norm
                                       : 0.0;
      if (cosine <= kFacing) continue;
      if (sides.sealed[s]) {
        faces_sealed = faces_sealed || distance[s] < h_m;
      } else {
        faces_open = faces_open || distance[s] < radius[i];
      }
    }
    const bool drained = faces_open || (!faces_sealed && any_open);
    out[i] = drained ? Boundary::drained : Boundary::sealed;
    ++(drained ? counts.drained : counts.sealed);
  }
  return counts;
}

}  // namespace rockcut::fluid::sp
