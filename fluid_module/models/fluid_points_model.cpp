#include "models/fluid_points_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "sp/format.hpp"

namespace rockcut::fluid::sp {

namespace {

SpParams with_smoothing_length(SpParams params, double h_m) {
  params.h_m = h_m;
  return params;
}

}  // namespace

FluidPointsModel::FluidPointsModel(const SpParams& params, PorePressureFactory make)
    : params_(params), make_(std::move(make)),
      // Until initialise() has counted the points, a model at the nominal spacing answers needs().
      points_(make_(with_smoothing_length(params, params.h_m * params.point_spacing))) {}

void FluidPointsModel::initialise(const StaticData& data) {
  const std::size_t n = data.radius.size();
  check_size(data.position, 2 * n, "the initial position");
  if (n == 0) throw std::invalid_argument("fluid points: no grains");
  grain_r_min_m_ = *std::min_element(data.radius.begin(), data.radius.end());
  restriction_.emplace(data.position, data.radius, params_.point_spacing);
  const PointRestriction& r = *restriction_;
  const std::size_t points = r.points();
  // A point stands for its cluster's area (the SP volumes start from it).
  std::vector<double> point_radius(points);
  for (std::size_t p = 0; p < points; ++p) {
    point_radius[p] = std::sqrt(r.area_m2()[p] / std::numbers::pi);
  }
  point_position_.resize(2 * points);
  r.restrict_to_points(data.position, point_position_, 2);

  // h grows by the points' spacing over the grains', measured: sqrt(grains / points).
  const double h_points =
      params_.h_m * std::sqrt(static_cast<double>(n) / static_cast<double>(points));
  points_ = make_(with_smoothing_length(params_, h_points));
  points_->initialise({point_radius, point_position_});
  point_displacement_.assign(2 * points, 0.0);
  point_velocity_.assign(2 * points, 0.0);
  point_force_.assign(2 * points, 0.0);
}

std::vector<StabilityLimit> FluidPointsModel::limits() const {
  std::vector<StabilityLimit> out;
  for (const StabilityLimit& l : points_->limits()) {
    if (l.kind != LimitKind::diffusion) continue;
    out.push_back(l);
    if (restriction_) {
      out.back().detail += " (on " + std::to_string(restriction_->points()) + " points for " +
                           std::to_string(restriction_->grains()) + " grains)";
    }
  }
  PorePressureModel::add_stiffness_limits(params_, grain_r_min_m_, out);
  return out;
}

void FluidPointsModel::step(double dt_s, double time_s, const Kinematics& k,
                            std::span<double> force) {
  if (!restriction_) throw std::logic_error("fluid points: step before initialise");
  const PointRestriction& r = *restriction_;
  const std::size_t n = r.grains();
  check_size(k.position, 2 * n, "position");
  check_size(force, 2 * n, "force");
  Kinematics points;
  r.restrict_to_points(k.position, point_position_, 2);
  points.position = point_position_;
  if (!k.displacement.empty()) {
    check_size(k.displacement, 2 * n, "displacement");
    r.restrict_to_points(k.displacement, point_displacement_, 2);
    points.displacement = point_displacement_;
  }
  if (!k.velocity_half.empty()) {
    check_size(k.velocity_half, 2 * n, "velocity_half");
    r.restrict_to_points(k.velocity_half, point_velocity_, 2);
    points.velocity_half = point_velocity_;
  }
  points.wall_segments = k.wall_segments;
  points_->step(dt_s, time_s, points, point_force_);
  r.spread_to_grains(point_force_, force, 2);
}

void FluidPointsModel::output(const std::string& field, std::vector<double>& values) const {
  const PointRestriction& r = *restriction_;
  points_->output(field, point_values_);
  if (point_values_.size() != r.points()) {
    throw std::invalid_argument("fluid points: field '" + field + "' is not one value per point");
  }
  values.resize(r.grains());
  r.show_on_grains(point_values_, values);
}

bool FluidPointsModel::probe(std::span<const double> position, const ProbeBox& box,
                             double& mean_pa, std::size_t& count) const {
  // Over the grains in the box, each with its point's pressure.
  const PointRestriction& r = *restriction_;
  grain_values_.resize(r.grains());
  r.show_on_grains(points_->pressure(), grain_values_);
  mean_excess_in_box(position, grain_values_, params_.p_hydro_pa, box, mean_pa, count);
  return true;
}

void FluidPointsModel::scalars(std::vector<std::pair<std::string, double>>& out) const {
  points_->scalars(out);
  out.emplace_back("points", static_cast<double>(restriction_ ? restriction_->points() : 0));
}

void FluidPointsModel::save_state(state::StateArchive& archive) const {
  points_->save_state(archive);
  archive.put_scalar("points", static_cast<double>(restriction_->points()));
}

void FluidPointsModel::load_state(const state::StateArchive& archive) {
  const std::size_t points = restriction_->points();
  if (!archive.has("points") || archive.scalar_as<std::size_t>("points") != points) {
    throw state::StateError(
        "the state is of a pore fluid on " +
        (archive.has("points") ? std::to_string(archive.scalar_as<std::size_t>("points")) +
                                     " points"
                               : std::string("every grain")) +
        ", this run's has " + std::to_string(points) + " (fluid.point_spacing)");
  }
  points_->load_state(archive);
}

std::unique_ptr<FluidModel> pore_pressure_model(const SpParams& params,
                                                const PorePressureFactory& make) {
  if (params.point_spacing > 1.0) return std::make_unique<FluidPointsModel>(params, make);
  return make(params);
}

}  // namespace rockcut::fluid::sp
