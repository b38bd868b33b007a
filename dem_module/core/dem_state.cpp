// The DEM's part of a checkpoint (DemSystem::save_state / load_state): everything that decides the
// next bit. A run resumed from it continues bit for bit as the run that wrote it: the particle
// arrays, the bonds with their shear springs, the contacts in list order with their tangential
// history (the order of the pair sums), the walls' offsets and listed pairs, the damping forces of
// the last evaluation (the F^n half of the damping trapezoid) and each pair's dashpots' last
// forces (the same for the dashpots), the ledger, the breaks, and the
// drift since the last neighbour-list rebuild (so the next rebuild comes at the same step).
// What the scene rebuilds at Init (radii, masses, settings, segments) is not saved.
#include <stdexcept>
#include <string>

#include "core/dem_system.hpp"

namespace rockcut::dem {

using state::StateArchive;
using state::StateError;

namespace {

// The dashpots' last forces (PairDashpots: normal, tangential) as a two-component member.
void put_dashpots(StateArchive& a, std::string_view name, const std::vector<PairDashpots>& d) {
  std::vector<double> v;
  v.reserve(2 * d.size());
  for (const PairDashpots& f : d) v.insert(v.end(), {f.normal, f.tangential});
  a.put(name, std::move(v), 2);
}

// A state written before the dashpots' trapezoid kept their last forces has none: they start at
// zero, which books the first step after the resume as if the pairs had just met.
void get_dashpots(const StateArchive& a, std::string_view name, std::vector<PairDashpots>& d,
                  std::size_t n) {
  d.assign(n, PairDashpots{});
  if (!a.has(name)) return;
  const auto v = a.values(name, 2 * n);
  for (std::size_t k = 0; k < n; ++k) d[k] = PairDashpots{v[2 * k], v[2 * k + 1]};
}

void check_index(std::string_view what, const std::vector<std::uint32_t>& v, std::size_t limit) {
  for (std::uint32_t i : v) {
    if (i >= limit) {
      throw StateError("state member \"" + std::string(what) + "\" refers to item " +
                       std::to_string(i) + " of " + std::to_string(limit));
    }
  }
}

}  // namespace

void BondSet::save_state(StateArchive& a) const {
  a.put_values("bond_i", i_);
  a.put_values("bond_j", j_);
  a.put("bond_rest_length_m", rest_length_);
  a.put("bond_shear_force_n_per_m", shear_force_);
  a.put("bond_released_at_break_j", released_at_break_);
  a.put_values("bond_broken", broken_);
  put_dashpots(a, "bond_dashpot_force_n_per_m", dashpot_);
  if (!damage_.empty()) a.put("bond_damage", damage_);
}

void BondSet::load_state(const StateArchive& a, const Particles& p) {
  const std::size_t particles = p.size();
  a.get_values("bond_i", i_);
  const std::size_t n = i_.size();
  a.get_values("bond_j", j_, n);
  a.get("bond_rest_length_m", rest_length_, n);
  a.get("bond_shear_force_n_per_m", shear_force_, n);
  // Breaks are removed within the step that flags them, so a checkpoint holds none flagged; a
  // state written under the member's former name (the normal force at the break) loads zeros.
  released_at_break_.assign(n, 0.0);
  if (a.has("bond_released_at_break_j")) a.get("bond_released_at_break_j", released_at_break_, n);
  a.get_values("bond_broken", broken_, n);
  get_dashpots(a, "bond_dashpot_force_n_per_m", dashpot_, n);
  // The damage of a softening law's bonds; the scene's law says whether there is one (a state
  // written under the brittle law resumes with every bond intact).
  damage_.clear();
  if (law_.softening_ratio > 0.0) {
    damage_.assign(n, 0.0);
    if (a.has("bond_damage")) a.get("bond_damage", damage_, n);
  }
  damaged_.assign(damage_.size(), 0);
  for (std::size_t k = 0; k < damage_.size(); ++k) damaged_[k] = damage_[k] > 0.0;
  check_index("bond_i", i_, particles);
  check_index("bond_j", j_, particles);
  refresh_partners(particles);
  refresh_pair_masses(p);
}

void ContactList::save_state(StateArchive& a) const {
  a.put_values("contact_i", i_);
  a.put_values("contact_j", j_);
  a.put("contact_shear_force_n_per_m", shear_force_);
  a.put("contact_rolling_moment_n", rolling_moment_);
  put_dashpots(a, "contact_dashpot_force_n_per_m", dashpot_);
}

void ContactList::load_state(const StateArchive& a, std::size_t particles) {
  a.get_values("contact_i", i_);
  a.get_values("contact_j", j_, i_.size());
  a.get("contact_shear_force_n_per_m", shear_force_, i_.size());
  a.get("contact_rolling_moment_n", rolling_moment_, i_.size());
  get_dashpots(a, "contact_dashpot_force_n_per_m", dashpot_, i_.size());
  check_index("contact_i", i_, particles);
  check_index("contact_j", j_, particles);
}

// Per body: velocity, offset, force and the previous step's force (x and y of each).
constexpr std::size_t kWallBodyValues = 8;

void WallSet::save_state(StateArchive& a) const {
  std::vector<double> bodies;
  bodies.reserve(kWallBodyValues * bodies_.size());
  for (const WallBody& b : bodies_) {
    bodies.insert(bodies.end(), {b.velocity_x, b.velocity_y, b.offset_x, b.offset_y, b.force_x,
                                 b.force_y, b.previous_force_x, b.previous_force_y});
  }
  a.put("wall_bodies", std::move(bodies), kWallBodyValues);
  a.put("wall_offset_at_rebuild_m", offset_at_rebuild_, 2);
  a.put_values("wall_pair_particle", particle_);
  a.put_values("wall_pair_segment", segment_);
  a.put("wall_pair_shear_force_n_per_m", shear_force_);
  a.put("wall_pair_rolling_moment_n", rolling_moment_);
  put_dashpots(a, "wall_pair_dashpot_force_n_per_m", dashpot_);
}

void WallSet::load_state(const StateArchive& a, std::size_t particles) {
  const auto bodies = a.values("wall_bodies", kWallBodyValues * bodies_.size());
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    const double* v = &bodies[kWallBodyValues * k];
    WallBody& b = bodies_[k];
    b.velocity_x = v[0];
    b.velocity_y = v[1];
    b.offset_x = v[2];
    b.offset_y = v[3];
    b.force_x = v[4];
    b.force_y = v[5];
    b.previous_force_x = v[6];
    b.previous_force_y = v[7];
  }
  a.get("wall_offset_at_rebuild_m", offset_at_rebuild_, 2 * bodies_.size());
  a.get_values("wall_pair_particle", particle_);
  a.get_values("wall_pair_segment", segment_, particle_.size());
  a.get("wall_pair_shear_force_n_per_m", shear_force_, particle_.size());
  a.get("wall_pair_rolling_moment_n", rolling_moment_, particle_.size());
  get_dashpots(a, "wall_pair_dashpot_force_n_per_m", dashpot_, particle_.size());
  check_index("wall_pair_particle", particle_, particles);
  check_index("wall_pair_segment", segment_, segments_.size());
}

void DemSystem::save_state(StateArchive& a) const {
  if (in_split_step_) throw std::logic_error("dem: state asked for inside a split step");
  const Particles& p = particles_;
  a.put("position_m", p.position, 2);
  a.put("velocity_m_s", p.velocity, 2);
  a.put("force_n_per_m", p.force, 2);
  a.put("external_force_n_per_m", p.external_force, 2);
  a.put("angular_velocity_rad_s", p.angular_velocity);
  a.put("torque_n", p.torque);
  a.put("damping_force", damping_force_, 3);
  bonds_.save_state(a);
  contacts_.save_state(a);
  walls_.save_state(a);
  std::vector<double> reactions;
  for (const ClampedGroup& g : clamped_) reactions.push_back(g.reaction_y_n_per_m);
  a.put("clamped_reaction_y_n_per_m", reactions);
  std::vector<double> break_time, break_xy, break_mode, break_pair;
  for (const BondBreak& b : breaks_) {
    break_time.push_back(b.time_s);
    break_xy.insert(break_xy.end(), {b.x_m, b.y_m});
    break_mode.push_back(static_cast<double>(b.mode));
    break_pair.insert(break_pair.end(), {static_cast<double>(b.i), static_cast<double>(b.j)});
  }
  a.put("break_time_s", break_time);
  a.put("break_position_m", break_xy, 2);
  a.put("break_mode", break_mode);
  a.put("break_pair", break_pair, 2);
  a.put("ledger_j", std::vector<double>{ledger_.boundary_work_j, ledger_.external_work_j,
                                        ledger_.gravity_work_j, ledger_.damping_j,
                                        ledger_.friction_j, ledger_.broken_bond_j,
                                        ledger_.viscous_damping_j, ledger_.rolling_j});
  a.put_scalar("ledger_viscous_bonds_j", ledger_.viscous_damping_bonds_j);
  a.put_scalar("ledger_bond_softening_j", ledger_.bond_softening_j);
  a.put_scalar("max_drift_m", max_drift_m_);
  a.put_scalar("dt_last_s", dt_last_);
  a.put_scalar("time_s", time_s_);
  a.put_scalar("steps", static_cast<double>(steps_));
  a.put_scalar("neighbour_rebuilds", static_cast<double>(rebuilds_));
  a.put_scalar("internal_forces_current", internal_forces_current_ ? 1.0 : 0.0);
  a.put_scalar("has_body_forces", has_body_forces_ ? 1.0 : 0.0);
  if (extrapolation_.on && !extrapolation_.last_force.empty()) {  // only where the scene extrapolates
    a.put("fluid_force_rate_n_per_m_s", extrapolation_.rate, 2);
    a.put("fluid_force_at_exchange_n_per_m", extrapolation_.last_force, 2);
    a.put_scalar("fluid_force_exchange_time_s", extrapolation_.last_time_s);
  }
  if (self_stiffness_.on && !self_stiffness_.k_pa.empty()) {  // only where the scene applies it
    a.put("fluid_self_stiffness_pa", self_stiffness_.k_pa, 3);
    a.put("fluid_self_stiffness_position_m", self_stiffness_.last_position, 2);
    a.put_scalar("fluid_self_stiffness_time_s", self_stiffness_.last_time_s);
  }
  const FluidForcePassivity& lag = passivity_;
  if (lag.on && !lag.position_at_exchange.empty()) {  // only where the scene corrects the lag
    a.put("lag_position_at_exchange_m", lag.position_at_exchange, 2);
    a.put("lag_force_at_exchange_n_per_m", lag.force_at_exchange, 2);
    a.put("lag_work_j", lag.work_j);
    a.put("lag_speed2_dt_m2_s", lag.speed2_dt);
    a.put("lag_residual_j", lag.residual_j);
    a.put("lag_coefficient_n_s_per_m2", lag.coefficient);
    a.put("lag_force_n_per_m", lag.force, 2);
    a.put_scalar("lag_exchange_step", static_cast<double>(lag.exchange_step));
    a.put_scalar("ledger_lag_correction_j", ledger_.lag_correction_j);
  }
}

void DemSystem::load_state(const StateArchive& a) {
  if (in_split_step_) throw std::logic_error("dem: state loaded inside a split step");
  // Validate everything, then assign: the members are loaded into a copy, which replaces this
  // system only when every size and index has been checked. A refused state leaves the system as
  // it was, so the next step cannot read a half-loaded list out of bounds.
  DemSystem loaded = *this;
  loaded.assign_state(a);
  *this = std::move(loaded);
}

void DemSystem::assign_state(const StateArchive& a) {
  Particles& p = particles_;
  const std::size_t n = p.size();
  a.get("position_m", p.position, 2 * n);
  a.get("velocity_m_s", p.velocity, 2 * n);
  a.get("force_n_per_m", p.force, 2 * n);
  a.get("external_force_n_per_m", p.external_force, 2 * n);
  a.get("angular_velocity_rad_s", p.angular_velocity, n);
  a.get("torque_n", p.torque, n);
  a.get("damping_force", damping_force_);
  if (!damping_force_.empty() && damping_force_.size() != 3 * n) {
    throw StateError("state member \"damping_force\" has " + std::to_string(damping_force_.size()) +
                     " values for " + std::to_string(n) + " particles");
  }
  bonds_.load_state(a, p);
  contacts_.load_state(a, n);
  walls_.load_state(a, n);
  const auto reactions = a.values("clamped_reaction_y_n_per_m", clamped_.size());
  for (std::size_t k = 0; k < clamped_.size(); ++k) clamped_[k].reaction_y_n_per_m = reactions[k];
  const auto time = a.values("break_time_s");
  const auto xy = a.values("break_position_m", 2 * time.size());
  std::vector<BreakMode> modes;
  std::vector<std::uint32_t> pairs;
  a.get_values("break_mode", modes, time.size());
  a.get_values("break_pair", pairs, 2 * time.size());
  check_index("break_pair", pairs, n);
  breaks_.clear();
  for (std::size_t k = 0; k < time.size(); ++k) {
    if (modes[k] != BreakMode::tensile && modes[k] != BreakMode::shear) {
      throw StateError("state member \"break_mode\" holds an unknown mode");
    }
    breaks_.push_back({modes[k], time[k], xy[2 * k], xy[2 * k + 1], pairs[2 * k], pairs[2 * k + 1]});
  }
  const auto ledger = a.values("ledger_j", 8);
  ledger_ = {ledger[0], ledger[1], ledger[2], ledger[3],
             ledger[4], ledger[5], ledger[6], ledger[7]};
  // A state written before the dashpots' dissipation was split by where it happens has no such
  // member: its bonds' part then counts from the resume.
  ledger_.viscous_damping_bonds_j =
      a.has("ledger_viscous_bonds_j") ? a.scalar("ledger_viscous_bonds_j") : 0.0;
  ledger_.bond_softening_j =
      a.has("ledger_bond_softening_j") ? a.scalar("ledger_bond_softening_j") : 0.0;
  max_drift_m_ = a.scalar("max_drift_m");
  dt_last_ = a.scalar("dt_last_s");
  time_s_ = a.scalar("time_s");
  steps_ = a.scalar_as<std::uint64_t>("steps");
  rebuilds_ = a.scalar_as<std::uint64_t>("neighbour_rebuilds");
  internal_forces_current_ = a.scalar("internal_forces_current") != 0.0;
  has_body_forces_ = a.scalar("has_body_forces") != 0.0;
  // An extrapolated run's line through its last two exchanges; a state without one (held
  // forces) starts the line afresh at the next exchange if the run extrapolates.
  extrapolation_ = FluidForceExtrapolation{};
  if (a.has("fluid_force_rate_n_per_m_s")) {
    extrapolation_.on = true;
    a.get("fluid_force_rate_n_per_m_s", extrapolation_.rate, 2 * n);
    a.get("fluid_force_at_exchange_n_per_m", extrapolation_.last_force, 2 * n);
    extrapolation_.last_time_s = a.scalar("fluid_force_exchange_time_s");
  }
  // The grain's own fluid stiffness of the last exchange; a state without one starts it at the
  // next exchange if the run applies it.
  self_stiffness_ = FluidSelfStiffness{};
  if (a.has("fluid_self_stiffness_pa")) {
    self_stiffness_.on = true;
    a.get("fluid_self_stiffness_pa", self_stiffness_.k_pa, 3 * n);
    a.get("fluid_self_stiffness_position_m", self_stiffness_.last_position, 2 * n);
    self_stiffness_.last_time_s = a.scalar("fluid_self_stiffness_time_s");
  }
  // The lag's observer; a state without one starts it afresh at the next exchange.
  passivity_ = FluidForcePassivity{};
  if (a.has("lag_position_at_exchange_m")) {
    FluidForcePassivity& lag = passivity_;
    lag.on = true;
    a.get("lag_position_at_exchange_m", lag.position_at_exchange, 2 * n);
    a.get("lag_force_at_exchange_n_per_m", lag.force_at_exchange, 2 * n);
    a.get("lag_work_j", lag.work_j, n);
    a.get("lag_speed2_dt_m2_s", lag.speed2_dt, n);
    a.get("lag_residual_j", lag.residual_j, n);
    a.get("lag_coefficient_n_s_per_m2", lag.coefficient, n);
    a.get("lag_force_n_per_m", lag.force, 2 * n);
    lag.exchange_step = a.scalar_as<std::uint64_t>("lag_exchange_step");
    ledger_.lag_correction_j = a.scalar("ledger_lag_correction_j");
  }
  // The thread shares of the restored lists, as after the rebuild that made them.
  update_force_windows();
}

}  // namespace rockcut::dem
