// What the `explicit` and `implicit` pore-pressure models share (paper sections 3.2-3.3): the
// neighbour lists, the SP geometry of each step, the boundary classification, the volumetric
// strain rate, and the force -grad p * pi r^2 (eq. 21). A model only says how p advances.
//
// One step (DESIGN section 3, fluid part): positions x^{n+N} and the strain field arrive; the
// geometry is updated on x^{n+N}; the volumetric strain rate is the corrected divergence (eq. 17)
// of the displacement since the last exchange divided by the fluid step (or of v^{n+N-1/2});
// the pressure advances by the fluid step (eq. 14) with the boundary values of section 3.3 and the
// clamp of eq. 22; the corrected gradient of the new pressure gives the force.
#pragma once

#include <string>
#include <vector>

#include "models/fluid_model.hpp"
#include "sp/boundary.hpp"
#include "sp/geometry.hpp"
#include "sp/kernel.hpp"
#include "sp/neighbours.hpp"
#include "sp/params.hpp"

namespace rockcut::fluid::sp {

class PorePressureModel : public FluidModel {
 public:
  explicit PorePressureModel(const SpParams& params);

  std::vector<std::string> needs() const override;
  std::vector<std::string> needs_static() const override { return {"radius", "position"}; }
  std::vector<std::string> provides() const override;
  void initialise(const StaticData& data) override;
  void step(double dt_s, double time_s, const Kinematics& kinematics,
            std::span<double> force) override;
  void output(const std::string& field, std::vector<double>& values) const override;
  void scalars(std::vector<std::pair<std::string, double>>& out) const override;

  // For tests and benchmarks.
  const SpParams& params() const { return params_; }
  std::span<const double> pressure() const { return pressure_; }
  std::span<double> mutable_pressure() { return pressure_; }
  std::span<const Boundary> boundary() const { return boundary_; }
  std::span<const double> strain_rate() const { return strain_rate_; }
  const Geometry& geometry() const { return geo_; }
  const NeighbourList& neighbour_list() const { return list_; }
  /// Solid fraction measured at initialise: sum(pi r^2) / sum(V) over interior particles.
  double packing_fraction() const { return packing_fraction_; }
  std::size_t cavitated() const { return cavitated_; }

 protected:
  /// Advances pressure_ by dt with the source -alpha M strain_rate_ (Pa/s), holding drained
  /// particles at p_hydro and clamping by eq. 22. Called once per step with dt > 0.
  virtual void advance(double dt_s) = 0;
  /// Model-specific scalars appended to the common ones.
  virtual void add_scalars(std::vector<std::pair<std::string, double>>&) const {}

  const SpParams params_;
  const WendlandC2 kernel_;
  const double diffusivity_m2_s_;
  NeighbourList list_;
  Geometry geo_;
  std::vector<double> radius_, lucy_volume_;
  std::vector<double> pressure_, strain_rate_, source_, work_, grad_;
  std::vector<Boundary> boundary_;
  Sides sides_;
  BoundaryCounts counts_;
  std::size_t cavitated_ = 0;

 private:
  double packing_fraction_ = 1.0;
};

}  // namespace rockcut::fluid::sp
