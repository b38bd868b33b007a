// A pore-pressure model (`explicit` or `implicit`) run on fewer points than grains
// (fluid.point_spacing > 1; docs/model.md, "Fewer fluid points than grains"). Each point is the
// centre of area of a fixed cluster of grains; the grains' motion is restricted to the points and
// the points' force spread back by the transpose (sp/point_restriction.hpp); the model on the
// points is the paper's, with the smoothing length grown by the points' measured spacing over the
// grains'. The DEM and the coupler see a model of the grains: every array in and out is per grain.
#pragma once

#include <functional>
#include <memory>
#include <optional>

#include "models/pore_pressure_model.hpp"
#include "sp/point_restriction.hpp"

namespace rockcut::fluid::sp {

using PorePressureFactory = std::function<std::unique_ptr<PorePressureModel>(const SpParams&)>;

class FluidPointsModel final : public FluidModel {
 public:
  FluidPointsModel(const SpParams& params, PorePressureFactory make);

  std::string name() const override { return points_->name(); }
  std::vector<std::string> needs() const override { return points_->needs(); }
  std::vector<std::string> needs_static() const override { return {"radius", "position"}; }
  std::vector<std::string> provides() const override { return points_->provides(); }
  /// The points' diffusion limit, and the stiffness limits of the lightest grain (the grains'
  /// own: a grain feels the points' stiffness through its weights, at most its full share).
  std::vector<StabilityLimit> limits() const override;
  void initialise(const StaticData& data) override;
  void step(double dt_s, double time_s, const Kinematics& kinematics,
            std::span<double> force) override;
  void output(const std::string& field, std::vector<double>& values) const override;
  bool probe(std::span<const double> position, const ProbeBox& box, double& mean_pa,
             std::size_t& count) const override;
  void scalars(std::vector<std::pair<std::string, double>>& out) const override;
  const wire::PhaseClock* phases() const override { return points_->phases(); }
  void save_state(state::StateArchive& archive) const override;
  void load_state(const state::StateArchive& archive) override;

  // For tests.
  const PorePressureModel& points_model() const { return *points_; }
  const PointRestriction& restriction() const { return *restriction_; }

 private:
  SpParams params_;
  PorePressureFactory make_;
  std::unique_ptr<PorePressureModel> points_;
  std::optional<PointRestriction> restriction_;
  double grain_r_min_m_ = 0.0;
  std::vector<double> point_position_, point_displacement_, point_velocity_, point_force_;
  mutable std::vector<double> point_values_, grain_values_;  // output and pressure nodes
};

/// The model `make` builds, on points when params.point_spacing > 1.
std::unique_ptr<FluidModel> pore_pressure_model(const SpParams& params,
                                                const PorePressureFactory& make);

}  // namespace rockcut::fluid::sp
