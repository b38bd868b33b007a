// Fluid points fewer than grains (fluid.point_spacing > 1): the pore-pressure model runs on points,
// each a fixed weighted mean of the grains around it, and hands its force back by the transpose.
//
// A point p is the grain of the initial packing nearest a node of a lattice `spacing` apart over
// the packing's bounding box (so that its sides have points on them), and any grain no point
// reaches. Its weights over the grains within `support` of it are the Wendland C2 kernel
// (sp/kernel.hpp) of their initial offsets d_j = x_j^0 - x_p^0, tilted to centre them on the
// point (the weights of maximum entropy with the kernel as prior, Arroyo and Ortiz 2006):
//   R_pj = W(|d_j|) exp(lambda . d_j) / sum_k W(|d_k|) exp(lambda . d_k),
// with lambda such that sum_j R_pj d_j = 0; they are positive and sum to 1. They are fixed: a
// point is a piece of material. Its displacement and velocity are
//   u_p = sum_j R_pj u_j   (the same for any per-grain vector),
// exact for a linear field (a point moves as the field at its own position: its grains' mean
// position is its own), and the force on grain j is
//   f_j = sum_p R_pj F_p   (R^T F),
// so that the power is the same on both sides, sum_p F_p . (R v)_p = sum_j (R^T F)_j . v_j, and
// the total force is kept (the rows sum to 1): the fluid's work on the grains is what the points
// receive, and the energy ledger stays exact. A per-point scalar is shown on the grains as
// sum_p R_pj a_p / sum_p R_pj. Both products are gathers over fixed compressed rows: the same bits
// at any thread count.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace rockcut::fluid::sp {

class PointRestriction {
 public:
  /// Chooses the points and their weights on the initial packing (`position` interleaved x, y
  /// [m]). Throws std::invalid_argument for a non-positive spacing or a support below it.
  PointRestriction(std::span<const double> position, double spacing_m, double support_m);

  std::size_t points() const { return point_grain_.size(); }
  std::size_t grains() const { return column_sum_.size(); }
  /// The grain each point was chosen at.
  const std::vector<int>& point_grain() const { return point_grain_; }
  /// sum_p R_pj: how much of the points' force grain j takes (0 for none).
  const std::vector<double>& column_sum() const { return column_sum_; }
  /// The point with the largest weight on grain j.
  const std::vector<int>& main_point() const { return main_point_; }
  double spacing_m() const { return spacing_m_; }
  double support_m() const { return support_m_; }

  /// out_p = sum_j R_pj in_j for `components` values per grain (out: components per point).
  void restrict_to_points(std::span<const double> grain, std::span<double> point,
                          int components) const;
  /// out_j = sum_p R_pj in_p (the transpose), `components` values each.
  void spread_to_grains(std::span<const double> point, std::span<double> grain,
                        int components) const;
  /// out_j = sum_p R_pj a_p / sum_p R_pj for a scalar per point (0 where no point reaches).
  void interpolate_to_grains(std::span<const double> point, std::span<double> grain) const;

 private:
  /// Tilts the prior weights row_weight_[first ..] of the point at grain g so that their mean
  /// position is the grain's, keeping them positive (the weights' maximum entropy).
  void centre_weights(std::span<const double> position, int g, std::size_t first);

  std::vector<double> scratch_;
  double spacing_m_, support_m_;
  std::vector<int> point_grain_;
  std::vector<std::size_t> row_start_;   // point p: grains row_grain_[row_start_[p] ..]
  std::vector<int> row_grain_;
  std::vector<double> row_weight_;
  std::vector<std::size_t> column_start_;  // grain j: points column_point_[column_start_[j] ..]
  std::vector<int> column_point_;
  std::vector<double> column_weight_;
  std::vector<double> column_sum_;
  std::vector<int> main_point_;
};

}  // namespace rockcut::fluid::sp
