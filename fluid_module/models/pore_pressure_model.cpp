#include "models/pore_pressure_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sp/cavitation.hpp"
#include "sp/format.hpp"
#include "sp/open_water_drag.hpp"
#include "sp/operators.hpp"
#include "sp/pressure_force.hpp"
#include "sp/storage_equation.hpp"

namespace rockcut::fluid::sp {

void check_size(std::span<const double> a, std::size_t expected, const char* what) {
  if (a.size() != expected) {
    throw std::invalid_argument(std::string("fluid: ") + what + " has " + std::to_string(a.size()) +
                                " values, expected " + std::to_string(expected));
  }
}

PorePressureModel::PorePressureModel(const SpParams& params)
    : params_(params), kernel_(params.h_m), diffusivity_m2_s_(params.diffusivity_m2_s()),
      list_(params.h_m, params.skin), step_op_(params.laplacian) {}

std::vector<std::string> PorePressureModel::needs() const {
  std::vector<std::string> out = {
      "position", params_.strain_from == StrainFrom::displacement ? "displacement" : "velocity_half"};
  if (params_.seal_at_walls) out.emplace_back("wall_segments");
  return out;
}

std::vector<StabilityLimit> PorePressureModel::limits() const {
  std::vector<StabilityLimit> out = {diffusion_limit()};
  out.back().kind = LimitKind::diffusion;
  if (radius_.empty()) return out;
  const double r_min = *std::min_element(radius_.begin(), radius_.end());
  add_stiffness_limits(params_, r_min, out);
  return out;
}

void PorePressureModel::add_stiffness_limits(const SpParams& params, double r_min_m,
                                             std::vector<StabilityLimit>& out) {
  // The pore fluid's stiffness under a lagged force (DESIGN section 5; see kFluidStiffnessC),
  // only when the DEM moves the particles by the fluid force.
  const double stiffness = params.alpha * params.bulk_modulus_pa;  // k_f [Pa]
  if (!params.dynamic_solid || !(stiffness > 0.0)) return;
  const double m_min = params.grain_density_kg_m3 * std::numbers::pi * r_min_m * r_min_m;
  const double local_dt = kFluidStiffnessC * params.local_damping * std::sqrt(m_min / stiffness);
  const double viscous_dt = kFluidViscousC * params.viscous_damping_ratio *
                            std::sqrt(m_min * params.normal_stiffness_pa) / stiffness;
  std::string formula = "lagged fluid force: ";
  if (params.viscous_damping_ratio > 0.0) {
    formula += "C alpha_d sqrt(m_min / (alpha M)) + C_v zeta sqrt(m_min k_n) / (alpha M) with C = " +
               fmt(kFluidStiffnessC) + ", local damping alpha_d = " + fmt(params.local_damping) +
               ", C_v = " + fmt(kFluidViscousC) + ", dashpots zeta = " +
               fmt(params.viscous_damping_ratio) + ", k_n = " + fmt(params.normal_stiffness_pa) +
               " Pa";
  } else {
    formula += "C alpha_d sqrt(m_min / (alpha M)) with C = " + fmt(kFluidStiffnessC) +
               ", local damping alpha_d = " + fmt(params.local_damping);
  }
  const double held_dt = local_dt + viscous_dt;
  out.push_back({"pore_fluid_stiffness", held_dt,
                 formula + ", m_min = " + fmt(m_min) + " kg/m, alpha M = " + fmt(stiffness) +
                     " Pa; binds only N > 1",
                 /*lag_only=*/true, /*remedy=*/"use coupling.fluid_force \"extrapolated\"",
                 LimitKind::pore_fluid_stiffness});
  // Without contact stiffness no grain vibrates on a contact: the held limit stands. Without
  // local damping the cut's own dissipation counts as a dashpot ratio zeta_0
  // (kFluidIntrinsicDampingRatio, measured so); under local damping the limit was measured
  // without it.
  const double k_n = params.normal_stiffness_pa;
  const bool intrinsic = !(params.local_damping > 0.0);
  const double extrapolated_held_dt =
      intrinsic ? held_dt + kFluidViscousC * kFluidIntrinsicDampingRatio *
                                std::sqrt(m_min * k_n) / stiffness
                : held_dt;
  const double extrapolated_dt =
      k_n > 0.0 ? kFluidExtrapolatedC * std::cbrt(extrapolated_held_dt * m_min / k_n) : held_dt;
  out.push_back({"pore_fluid_stiffness_extrapolated", extrapolated_dt,
                 "extrapolated fluid force: C_x cbrt(dt_held m_min / k_n) with C_x = " +
                     fmt(kFluidExtrapolatedC) + ", dt_held = " + fmt(extrapolated_held_dt) +
                     (intrinsic ? " s (zeta + zeta_0, zeta_0 = " +
                                      fmt(kFluidIntrinsicDampingRatio) + " the cut's own damping)"
                                : std::string(" s")) +
                     ", k_n = " + fmt(k_n) + " Pa; binds only N > 1",
                 /*lag_only=*/true, /*remedy=*/{}, LimitKind::pore_fluid_stiffness_extrapolated});
}

bool PorePressureModel::probe(std::span<const double> position, const ProbeBox& box,
                              double& mean_pa, std::size_t& count) const {
  mean_excess_in_box(position, pressure_, params_.p_hydro_pa, box, mean_pa, count);
  return true;
}

void mean_excess_in_box(std::span<const double> position, std::span<const double> pressure,
                        double p_hydro_pa, const ProbeBox& box, double& mean_pa,
                        std::size_t& count) {
  double sum = 0.0;
  count = 0;
  for (std::size_t i = 0; i < pressure.size() && 2 * i + 1 < position.size(); ++i) {
    const double x = position[2 * i], y = position[2 * i + 1];
    if (x < box.x_min_m || x > box.x_max_m || y < box.y_min_m || y > box.y_max_m) continue;
    sum += pressure[i] - p_hydro_pa;
    ++count;
  }
  mean_pa = count ? sum / static_cast<double>(count) : 0.0;
}

std::vector<std::string> PorePressureModel::provides() const {
  return {"pressure", "boundary", "div_r", "volumetric_strain_rate", "sp_volume"};
}

void PorePressureModel::initialise(const StaticData& data) {
  const std::size_t n = data.radius.size();
  check_size(data.position, 2 * n, "the initial position");
  radius_.assign(data.radius.begin(), data.radius.end());
  sides_.fit(data.position);
  sides_.sealed = params_.sealed;

  // The volumes m_j / rho_j of eq. 24 are pi r_j^2 / phi with phi the solid fraction of the
  // specimen, measured here: sum(pi r^2) / sum(V) over the particles that the SP volumes already
  // mark as interior. (With the SP volumes themselves in eq. 24 the surface particles' volumes
  // grow to make up for their missing neighbours, and div r at a surface comes close to 1.5.)
  list_.build(data.position);
  lucy_volume_.assign(n, 0.0);
  update_geometry(list_, kernel_, data.position, lucy_volume_, params_.volume_iterations, geo_);
  lucy_volume_ = geo_.volume;
  update_geometry(list_, kernel_, data.position, lucy_volume_, params_.volume_iterations, geo_);
  double area = 0.0, volume = 0.0, area_all = 0.0, volume_all = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = std::numbers::pi * radius_[i] * radius_[i];
    area_all += a;
    volume_all += geo_.volume[i];
    if (geo_.div_r[i] > params_.surface_div_r) {
      area += a;
      volume += geo_.volume[i];
    }
  }
  packing_fraction_ = volume > 0.0 ? area / volume : (volume_all > 0.0 ? area_all / volume_all : 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    lucy_volume_[i] = std::numbers::pi * radius_[i] * radius_[i] / packing_fraction_;
  }
  update_geometry(list_, kernel_, data.position, lucy_volume_, params_.volume_iterations, geo_);

  // Initial pressure: p_hydro (section 4), plus the optional Gaussian pulse.
  pressure_.assign(n, params_.p_hydro_pa);
  if (params_.pulse_amplitude_pa != 0.0) {
    const double s2 = params_.pulse_sigma_m * params_.pulse_sigma_m;
    for (std::size_t i = 0; i < n; ++i) {
      const double dx = data.position[2 * i] - params_.pulse_x_m;
      const double dy = data.position[2 * i + 1] - params_.pulse_y_m;
      pressure_[i] += params_.pulse_amplitude_pa * std::exp(-(dx * dx + dy * dy) / (2.0 * s2));
    }
  }
  strain_rate_.assign(n, 0.0);
  source_.assign(n, 0.0);
  area_excess_.assign(n, 0.0);
  update_share();
  area_.resize(n);
  for (std::size_t i = 0; i < n; ++i) area_[i] = std::numbers::pi * radius_[i] * radius_[i];
  laplacian_.assign(n, 0.0);
  grad_.assign(2 * n, 0.0);
  boundary_.assign(n, Boundary::interior);
  counts_ = classify_boundary(geo_.div_r, geo_.normal, params_.surface_div_r, params_.h_m,
                              data.position, radius_, sides_, boundary_);
}

void PorePressureModel::step(double dt_s, double /*time_s*/, const Kinematics& k,
                             std::span<double> force) {
  const std::size_t n = radius_.size();
  check_size(k.position, 2 * n, "position");
  check_size(force, 2 * n, "force");
  if (!(dt_s >= 0.0) || !std::isfinite(dt_s)) {
    throw std::invalid_argument("fluid: step with dt_s = " + std::to_string(dt_s));
  }
  const auto count = static_cast<std::ptrdiff_t>(n);
  phases_.start();
  const Staleness stale = staleness(k.position, k.wall_segments);
  phases_.lap(kStaleness);
  bool local = false;
  if (stale == Staleness::particles) {
    const bool rebuilt = list_.update(k.position);
    local = !rebuilt && params_.geometry_refresh > 0.0 && refresh_locally(k.position);
    if (!local) {
      update_geometry(list_, kernel_, k.position, lucy_volume_, params_.volume_iterations, geo_);
    }
    update_share();
    ++geometry_updates_;
    local_updates_ += local;
    rows_recomputed_ += local ? refresh_.coefficient_rows.size() : n;
  } else if (stale == Staleness::walls) {
    // Only a wall (the tool) has moved: the kernel sums do not see walls, so only the boundary
    // (which particles the walls seal) is recomputed.
    ++boundary_updates_;
  }
  phases_.lap(kGeometry);
  if (stale != Staleness::fresh) {
    self_stiffness_stale_ = true;
    // On the geometry's positions X' (the current ones after a full update).
    counts_ = classify_boundary(geo_.div_r, geo_.normal, params_.surface_div_r, params_.h_m,
                                geo_.position, radius_, sides_, boundary_, k.wall_segments);
    walls_at_geometry_.assign(k.wall_segments.begin(), k.wall_segments.end());
  }
  phases_.lap(kBoundary);
  // The step's coefficients follow the geometry.
  if (step_op_.version() != geo_.version) {
    if (local) {
      step_op_.rebuild_rows(geo_, refresh_.coefficient_rows);
    } else {
      step_op_.build(geo_);
    }
  }
  phases_.lap(kGeometry);

  if (dt_s > 0.0) {
    // Volumetric strain rate (eq. 17), then the source term -alpha M d(eps_v)/dt of eq. 14.
    const bool from_displacement = params_.strain_from == StrainFrom::displacement;
    const std::span<const double> field = from_displacement ? k.displacement : k.velocity_half;
    check_size(field, 2 * n, from_displacement ? "displacement" : "velocity_half");
    if (laplacian_in_step_) {
      step_op_.divergence_laplacian(geo_, field, pressure_, strain_rate_, laplacian_);
    } else {
      step_op_.divergence(geo_, field, strain_rate_);
    }
    // Per-particle loops on the model's threads, here and below: the same bits at any count.
    const double am = params_.alpha * params_.bulk_modulus_pa;
    double* rate = strain_rate_.data();
    double* source = source_.data();
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < count; ++i) {
      if (from_displacement) rate[i] /= dt_s;
      source[i] = storage_source(am, rate[i]);
    }
    phases_.lap(kPasses);
    advance(dt_s);
  } else {
    // t = 0: forces of the initial state only; the drained particles take their boundary value.
    std::fill(strain_rate_.begin(), strain_rate_.end(), 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (boundary_[i] == Boundary::drained) pressure_[i] = params_.p_hydro_pa;
    }
  }
  const double* p = pressure_.data();
  std::size_t cavitated = 0;
  if (params_.cavitation) {
    const double p_min = params_.p_min_pa;
#pragma omp parallel for schedule(static) reduction(+ : cavitated)
    for (std::ptrdiff_t i = 0; i < count; ++i) cavitated += at_vapour_pressure(p[i], p_min);
  }
  cavitated_ = cavitated;
  phases_.lap(kAdvance);

  if (params_.force_form == ForceForm::adjoint) {
    // The excess pressure acts on share_ (update_share): g_i = A_i (p_i - p_hydro) [N/m].
    const double* share = share_.data();
    double* g = area_excess_.data();
    const double p_hydro = params_.p_hydro_pa;
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < count; ++i) g[i] = share[i] * (p[i] - p_hydro);
    step_op_.adjoint_force(geo_, area_excess_, force);
  } else {
    // Eq. 21 with d = 2 r and unit thickness: F = -grad p * pi r^2 [N per m].
    gradient(geo_, pressure_, grad_);
    gradient_pressure_force(grad_, area_, force);
  }
  drag_power_w_per_m_ = 0.0;
  if (params_.open_water_drag && dt_s > 0.0) add_drag(dt_s, k, force);
  phases_.lap(kForce);
}

bool PorePressureModel::self_stiffness(std::vector<double>& out) {
  const std::size_t n = radius_.size();
  if (self_stiffness_stale_ || self_stiffness_.size() != 3 * n ||
      step_op_.version() != geo_.version) {
    // w_k = alpha M A_k where the pressure answers the strain, 0 where it is held (drained).
    const double am = params_.alpha * params_.bulk_modulus_pa;
    stiffness_weight_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      stiffness_weight_[i] = boundary_[i] == Boundary::drained ? 0.0 : am * share_[i];
    }
    self_stiffness_.resize(3 * n);
    step_op_.self_stiffness(geo_, stiffness_weight_, self_stiffness_);
    self_stiffness_stale_ = false;
  }
  out.assign(self_stiffness_.begin(), self_stiffness_.end());
  return true;
}

void PorePressureModel::add_drag(double dt_s, const Kinematics& k, std::span<double> force) {
  // The grains' mean velocity over the interval: the displacement since the last exchange over
  // the fluid step, or v^{n+N-1/2} where that is what the model receives. One thread, in particle
  // order: only the drained grains pay, and the power's sum has the same bits at any thread count.
  const bool from_displacement = params_.strain_from == StrainFrom::displacement;
  const std::span<const double> field = from_displacement ? k.displacement : k.velocity_half;
  const double to_velocity = from_displacement ? 1.0 / dt_s : 1.0;
  double power = 0.0;
  for (std::size_t i = 0; i < radius_.size(); ++i) {
    if (boundary_[i] != Boundary::drained) continue;
    const double vx = field[2 * i] * to_velocity, vy = field[2 * i + 1] * to_velocity;
    double fx = 0.0, fy = 0.0;
    add_open_water_drag(radius_[i], vx, vy, params_.water_density_kg_m3, params_.viscosity_pa_s,
                        fx, fy);
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
    power += fx * vx + fy * vy;
  }
  drag_power_w_per_m_ = power;
  drag_work_j_ += power * dt_s;
}

void PorePressureModel::update_share() {
  // The area the excess pressure acts on: the grains' share phi V_i of the SP volume (phi the
  // solid fraction measured at initialise), smooth where pi r_i^2 jumps from grain to grain.
  // Summed over the grains it is sum pi r^2, as in eq. 21. It changes only with the geometry.
  share_.resize(geo_.volume.size());
  for (std::size_t i = 0; i < share_.size(); ++i) share_[i] = packing_fraction_ * geo_.volume[i];
}

bool PorePressureModel::refresh_locally(std::span<const double> position) {
  // The particles that moved more than kLocalMoveFraction of the refresh distance take their new
  // positions; the others lag by less than the distance, as with a full update's guarantee.
  const double limit = kLocalMoveFraction * params_.geometry_refresh * params_.h_m;
  const double limit2 = limit * limit;
  const double* x = position.data();
  const double* x0 = geo_.position.data();
  moved_.clear();
  for (std::size_t i = 0; i < radius_.size(); ++i) {
    const double dx = x[2 * i] - x0[2 * i], dy = x[2 * i + 1] - x0[2 * i + 1];
    if (dx * dx + dy * dy > limit2) moved_.push_back(static_cast<int>(i));
  }
  return refresh_geometry(list_, kernel_, position, moved_, lucy_volume_,
                          params_.volume_iterations, kLocalMaxFraction, refresh_, geo_);
}

PorePressureModel::Staleness PorePressureModel::staleness(std::span<const double> position,
                                                          std::span<const double> walls) const {
  if (!(params_.geometry_refresh > 0.0) || position.size() != geo_.position.size() ||
      walls.size() != walls_at_geometry_.size()) {
    return Staleness::particles;
  }
  // Squared distances against (refresh h)^2: one pass, no square roots.
  const double limit = params_.geometry_refresh * params_.h_m;
  const double limit2 = limit * limit;
  const double* x = position.data();
  const double* x0 = geo_.position.data();
  const auto n = static_cast<std::ptrdiff_t>(position.size() / 2);
  double moved2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : moved2)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const double dx = x[2 * i] - x0[2 * i], dy = x[2 * i + 1] - x0[2 * i + 1];
    moved2 = std::max(moved2, dx * dx + dy * dy);
  }
  if (moved2 > limit2) return Staleness::particles;
  for (std::size_t k = 0; k + 1 < walls.size(); k += 2) {  // both ends of every segment
    const double dx = walls[k] - walls_at_geometry_[k];
    const double dy = walls[k + 1] - walls_at_geometry_[k + 1];
    if (dx * dx + dy * dy > limit2) return Staleness::walls;
  }
  return Staleness::fresh;
}

void PorePressureModel::output(const std::string& field, std::vector<double>& values) const {
  if (field == "pressure") {
    values.assign(pressure_.begin(), pressure_.end());
  } else if (field == "boundary") {
    values.resize(boundary_.size());
    for (std::size_t i = 0; i < boundary_.size(); ++i) values[i] = static_cast<double>(boundary_[i]);
  } else if (field == "div_r") {
    values.assign(geo_.div_r.begin(), geo_.div_r.end());
  } else if (field == "volumetric_strain_rate") {
    values.assign(strain_rate_.begin(), strain_rate_.end());
  } else if (field == "sp_volume") {
    values.assign(geo_.volume.begin(), geo_.volume.end());
  } else {
    throw std::invalid_argument(name() + " provides no field '" + field + "'");
  }
}

void PorePressureModel::scalars(std::vector<std::pair<std::string, double>>& out) const {
  out.clear();
  const auto [lo, hi] = std::minmax_element(pressure_.begin(), pressure_.end());
  out.emplace_back("pressure_min_pa", lo == pressure_.end() ? 0.0 : *lo);
  out.emplace_back("pressure_max_pa", hi == pressure_.end() ? 0.0 : *hi);
  out.emplace_back("drained_particles", static_cast<double>(counts_.drained));
  out.emplace_back("sealed_particles", static_cast<double>(counts_.sealed));
  out.emplace_back("cavitated_particles", static_cast<double>(cavitated_));
  out.emplace_back("neighbour_builds", static_cast<double>(list_.builds()));
  out.emplace_back("geometry_updates", static_cast<double>(geometry_updates_));
  out.emplace_back("geometry_local_updates", static_cast<double>(local_updates_));
  out.emplace_back("geometry_rows_recomputed", static_cast<double>(rows_recomputed_));
  out.emplace_back("boundary_updates", static_cast<double>(boundary_updates_));
  if (params_.open_water_drag) {
    out.emplace_back("drag_power_w_per_m", drag_power_w_per_m_);
    out.emplace_back("drag_work_j", drag_work_j_);
  }
  add_scalars(out);
}

}  // namespace rockcut::fluid::sp
