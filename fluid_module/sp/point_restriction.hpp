// Fluid points fewer than grains (fluid.point_spacing > 1): the pore-pressure model runs on points,
// each the centre of area of a fixed cluster of grains, and hands its force back to them.
//
// Each grain joins the nearest node of a lattice about `spacing_grains` mean grain spacings
// (sqrt(area / grains) over the initial packing's bounding box) apart over that box, with nodes
// on its four sides (so that the clusters there, half and quarter ones, have their centres near
// the sides, where the pore fluid drains or is sealed), for good: a point's cluster is a piece
// of material; a node without grains holds no point. With
// a_j = pi r_j^2 and A_p the cluster's area, the weights are
//   R_pj = a_j / A_p   (j in the cluster of p; sum_j R_pj = 1),
// a point's position, displacement and velocity are its cluster's centre of area, and its mean
// (the centre of mass for grains of one density),
//   x_p = sum_j R_pj x_j,   u_p = sum_j R_pj u_j,
// exact for a linear field (u_p is the field at x_p), and the force on grain j of cluster p is
//   f_j = R_pj F_p   (R^T F: the point's force spread by area),
// so that the power is the same on both sides, sum_p F_p . (R v)_p = sum_j (R^T F)_j . v_j, the
// total force is kept, and a uniform force per area on the points is one on the grains. The
// fluid's work on the grains is what the points receive, and the energy ledger stays exact. A
// per-point scalar is shown on each grain of its cluster. Both products run over fixed arrays:
// the same bits at any thread count.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace rockcut::fluid::sp {

class PointRestriction {
 public:
  /// Chooses the points and their clusters on the initial packing (`position` interleaved x, y
  /// [m], `radius` [m]), `spacing_grains` mean grain spacings apart. Throws
  /// std::invalid_argument for a non-positive spacing, positions that are not finite, or grains
  /// that do not span an area.
  PointRestriction(std::span<const double> position, std::span<const double> radius,
                   double spacing_grains);

  std::size_t points() const { return area_m2_.size(); }
  std::size_t grains() const { return point_of_.size(); }
  /// The lattice's spacing in x and y [m].
  const double* node_spacing_m() const { return node_spacing_m_; }
  /// The point whose cluster grain j belongs to.
  const std::vector<int>& point_of() const { return point_of_; }
  /// A_p, the area of point p's cluster [m^2].
  const std::vector<double>& area_m2() const { return area_m2_; }

  /// point_p = sum_j R_pj grain_j for `components` (1 or 2) values per grain and per point.
  void restrict_to_points(std::span<const double> grain, std::span<double> point,
                          int components) const;
  /// grain_j = R_pj point_p (the transpose), `components` values each.
  void spread_to_grains(std::span<const double> point, std::span<double> grain,
                        int components) const;
  /// grain_j = point_p of its cluster, one value each.
  void show_on_grains(std::span<const double> point, std::span<double> grain) const;

 private:
  double node_spacing_m_[2] = {0.0, 0.0};
  std::vector<int> point_of_;
  std::vector<double> weight_, area_m2_;  // R_pj of each grain in its cluster; A_p
  std::vector<std::size_t> cluster_start_;  // point p: grains cluster_[cluster_start_[p] ..]
  std::vector<int> cluster_;
};

}  // namespace rockcut::fluid::sp
