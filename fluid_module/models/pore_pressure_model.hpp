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

#include <cstdint>
#include <string>
#include <vector>

#include "models/fluid_model.hpp"
#include "sp/boundary.hpp"
#include "sp/geometry.hpp"
#include "sp/kernel.hpp"
#include "sp/neighbours.hpp"
#include "sp/params.hpp"
#include "sp/step_operator.hpp"

namespace rockcut::fluid::sp {

/// Lagged fluid force (N > 1): the force computed at an exchange is held for the N DEM steps of
/// the fluid step. Undrained, the pore fluid stiffens each grain by about k_f = alpha M (eqs. 14
/// and 21), and a spring force lagged by ~dt_f / 2 is a negative damping of about k_f dt_f / 2
/// that the DEM's damping must outweigh. Local damping (eq. 10) is worth about alpha_d m omega_f
/// with omega_f = sqrt(k_f / m); a dashpot of ratio zeta on a grain's normal spring k_n is worth
/// c = 2 zeta sqrt(m_eff k_n). Hence the limit, the two terms adding when both act,
///   dt_f <= kFluidStiffnessC * alpha_d * sqrt(m_min / (alpha M))
///         + kFluidViscousC * zeta * sqrt(m_min k_n) / (alpha M),
/// each constant a factor 2 below the smallest unstable step measured at 2000 m, where nothing
/// cavitates (local: alpha_d 0.7; viscous: zeta 0.1 on the reduced cut with a fixed base, N = 4
/// stable, N = 6 and 7 stopped by the energy guard: C_v = 0.5 x 9.54e-7 s / (0.1 x 6.39e-6 s);
/// docs/model.md, "Damping"; N = 5, 7.95e-7 s, was stopped too, 14 ms into the cut, so C_v is
/// 1.66 below the smallest unstable step). It binds only N > 1: N = 1 is always allowed, also
/// without damping.
inline constexpr double kFluidStiffnessC = 1.5;
inline constexpr double kFluidViscousC = 0.75;

/// Extrapolated fluid force (Coupling.fluid_force "extrapolated"): between exchanges the DEM
/// applies F^m + s (F^m - F^{m-1}) / dt_f at s after the exchange. For a grain vibrating at
/// omega, the error of that line is F'' s (s + dt_f) / 2 (a stiffness, no work over a period)
/// plus F''' s (dt_f^2 - s^2) / 6, whose work averages to a negative damping of
/// k_f omega^2 dt_f^3 / 24 where the held force's is k_f dt_f / 2. The damping the held limit
/// allows for, worth k_f dt_held / 2, then bounds
///   dt_f^3 <= 12 dt_held / omega^2, omega^2 = k_n / m_min (the lightest grain on its contact),
/// so dt_f <= kFluidExtrapolatedC * cbrt(dt_held m_min / k_n), with dt_held the held limit
/// above (which carries the measured constants and both dampings). Without local damping the
/// cut damps itself as well (friction, breaking bonds, the pore fluid's own flow): dt_held then
/// takes zeta + kFluidIntrinsicDampingRatio for zeta. Measured at 2000 m, where nothing
/// cavitates, on the reduced cut with the base held, 20 ms: the smallest step stopped by the
/// energy guard was N = 4 (7.03e-7 s) with no dashpots, 5 (8.75e-7 s) at zeta 0.005, 6
/// (1.03e-6 s) at zeta 0.02 and 10 (1.59e-6 s) at zeta 0.1 (N = 9 ran at 0.05 and 0.1). Its cube
/// goes as zeta + zeta_0 with zeta_0 = 0.0095 (the line through no dashpots and zeta 0.1), and
/// C_x = 0.5 x 1.59e-6 s / cbrt(dt_held(0.1 + zeta_0) 5.64e-3 kg/m / 7.25e9 Pa) = 1.067 puts the
/// limit a factor 2.0-2.2 below each of them (docs/model.md, "The coupling interval and the pore
/// fluid's stiffness"). Under local damping the line is worse than the held force, and the
/// formula (without zeta_0, which was measured without it) says so: on the paper's reduced cut
/// at 2000 m (alpha_d 0.7) N = 14 ran and N = 20 (3.5 us) was stopped extrapolated, where N = 20
/// ran held; the formula gives 1.33 us there, 2.6 times below the unstable step.
inline constexpr double kFluidExtrapolatedC = 1.067;
inline constexpr double kFluidIntrinsicDampingRatio = 0.0095;

/// A local geometry refresh (docs/model.md, "Reusing the geometry") moves the particles that
/// have moved more than this fraction of fluid.geometry_refresh_distance, not only the one that
/// crossed it: the particles near the tool move alike, and taking them along with the first
/// postpones the next refresh, at the cost of a few more rows.
inline constexpr double kLocalMoveFraction = 0.5;
/// Above this fraction of the particles in its rings, a local refresh gives way to a full update,
/// which sweeps the rows in order without the rings' bookkeeping.
inline constexpr double kLocalMaxFraction = 0.5;

/// Throws std::invalid_argument naming `what` unless `a` holds `expected` values.
void check_size(std::span<const double> a, std::size_t expected, const char* what);

/// The mean of p - p_hydro [Pa] over the particles whose centre lies in `box`, and their count
/// (FluidModel::probe).
void mean_excess_in_box(std::span<const double> position, std::span<const double> pressure,
                        double p_hydro_pa, const ProbeBox& box, double& mean_pa,
                        std::size_t& count);

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
  const wire::PhaseClock* phases() const override { return &phases_; }
  /// K_ii of the current geometry and boundary (sp/self_stiffness.cpp), recomputed only after
  /// either changed.
  bool self_stiffness(std::vector<double>& out) override;
  /// The model's diffusion limit, then the pore fluid's stiffness limit (when the DEM is dynamic).
  std::vector<StabilityLimit> limits() const final;
  /// Appends the pore fluid's stiffness limits (held, then extrapolated) for the lightest grain of
  /// radius r_min_m, when the DEM moves the particles by the fluid force.
  static void add_stiffness_limits(const SpParams& params, double r_min_m,
                                   std::vector<StabilityLimit>& out);
  /// Power of the open water's drag in the last step [W/m] (0 without fluid.open_water_drag).
  double drag_power_w_per_m() const { return drag_power_w_per_m_; }
  bool probe(std::span<const double> position, const ProbeBox& box, double& mean_pa,
             std::size_t& count) const override;
  /// Checkpoint and restart (models/pore_pressure_state.cpp).
  void save_state(state::StateArchive& archive) const final;
  void load_state(const state::StateArchive& archive) final;

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
  /// How many times step() recomputed the SP geometry (see SpParams::geometry_refresh).
  std::uint64_t geometry_updates() const { return geometry_updates_; }
  /// Of those, how many were local (refresh_geometry: only the rows near the moved particles).
  std::uint64_t local_updates() const { return local_updates_; }
  /// How many times step() recomputed only the boundary, because only a wall had moved.
  std::uint64_t boundary_updates() const { return boundary_updates_; }

 protected:
  /// The step limit of the model's own time integration of eq. 14 (stability or accuracy).
  virtual StabilityLimit diffusion_limit() const = 0;
  /// Advances pressure_ by dt with the source -alpha M strain_rate_ (Pa/s), holding drained
  /// particles at p_hydro and clamping by eq. 22. Called once per step with dt > 0; with
  /// laplacian_in_step_ set, laplacian_ then holds the eq. 20 Laplacian of pressure_.
  virtual void advance(double dt_s) = 0;
  /// The model's own state between steps, beside the common one (models/pore_pressure_state.cpp).
  virtual void save_model_state(state::StateArchive&) const {}
  virtual void load_model_state(const state::StateArchive&) {}
  /// Model-specific scalars appended to the common ones.
  virtual void add_scalars(std::vector<std::pair<std::string, double>>&) const {}

  const SpParams params_;
  const WendlandC2 kernel_;
  const double diffusivity_m2_s_;
  NeighbourList list_;
  Geometry geo_;
  std::vector<double> radius_, lucy_volume_;
  std::vector<double> pressure_, strain_rate_, source_, grad_;
  /// Set by a model whose advance() needs lap p^n (the explicit one): step() then computes it in
  /// the divergence's pass over the pairs (divergence_laplacian), into laplacian_ [Pa/m^2].
  bool laplacian_in_step_ = false;
  std::vector<double> laplacian_;
  std::vector<double> area_excess_, area_;  // share_ (p - p_hydro) [N/m]; pi r^2 [m^2]
  std::vector<double> share_;          // phi V_i [m^2], set with the geometry (update_share)
  /// The step's divergence, Laplacian and adjoint force as per-pair coefficients of the current
  /// geometry, rebuilt when the geometry changes.
  StepOperator step_op_;
  std::vector<Boundary> boundary_;
  Sides sides_;
  BoundaryCounts counts_;
  std::size_t cavitated_ = 0;
  /// What the open water's drag did on the grains in the last step, sum F . v [W/m] (<= 0), and
  /// since the start, sum of power x fluid step [J/m] (a checkpoint keeps it).
  double drag_power_w_per_m_ = 0.0;
  double drag_work_j_ = 0.0;

 private:
  /// What has moved more than geometry_refresh h since the geometry was computed: a particle
  /// (always with geometry_refresh 0 or a changed particle or wall count), else a wall end.
  enum class Staleness { fresh, walls, particles };
  Staleness staleness(std::span<const double> position, std::span<const double> walls) const;
  /// A local refresh of the geometry (refresh_geometry) around the particles that moved more
  /// than kLocalMoveFraction of the refresh distance; false if it would not pay (then nothing
  /// changed).
  bool refresh_locally(std::span<const double> position);
  /// share_ = phi V_i for the current geometry: the area the excess pressure acts on.
  void update_share();
  /// Adds the open water's drag (sp/open_water_drag.hpp) on the drained grains to `force`.
  void add_drag(double dt_s, const Kinematics& k, std::span<double> force);

  // Indices into phases_: the staleness test, the neighbour lists and SP geometry (with the
  // step's coefficients), the boundary, the passes over the pairs, the pressure's advance, the
  // force.
  enum StepPhase : std::size_t { kStaleness, kGeometry, kBoundary, kPasses, kAdvance, kForce };
  wire::PhaseClock phases_{{"staleness", "geometry", "boundary", "passes", "advance", "force"}};
  double packing_fraction_ = 1.0;
  std::vector<double> walls_at_geometry_;  // wall segments of the current geometry [m]
  std::uint64_t geometry_updates_ = 0;
  std::uint64_t boundary_updates_ = 0;  // walls moved, particles not: the boundary alone
  std::uint64_t local_updates_ = 0;
  std::uint64_t rows_recomputed_ = 0;  // over all geometry updates (a full one: every row)
  std::vector<int> moved_;  // the particles a local refresh moves
  // self_stiffness(): the last K_ii, and whether the geometry or boundary changed since.
  std::vector<double> self_stiffness_, stiffness_weight_;
  bool self_stiffness_stale_ = true;
  LocalRefresh refresh_;
};

}  // namespace rockcut::fluid::sp
