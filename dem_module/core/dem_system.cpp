#include "core/dem_system.hpp"

#include <algorithm>
#include <stdexcept>

namespace rockcut::dem {

DemSystem::DemSystem(Particles particles, const DemSettings& settings)
    : particles_(std::move(particles)), settings_(settings) {
  compute_internal_forces();
  add_external_forces();
}

void DemSystem::half_kick(double dt) {
  const std::size_t n = particles_.size();
  double* v = particles_.velocity.data();
  const double* f = particles_.force.data();
  const double* inv_m = particles_.inv_mass.data();
  const double half_dt = 0.5 * dt;
  for (std::size_t i = 0; i < n; ++i) {
    v[2 * i] += half_dt * f[2 * i] * inv_m[i];
    v[2 * i + 1] += half_dt * f[2 * i + 1] * inv_m[i];
  }
}

void DemSystem::set_prescribed_velocity(double t) {
  const PrescribedMotion& m = *settings_.prescribed_motion;
  const bool active = t >= m.start_time_s && t < m.end_time_s;
  const double exx = active ? m.strain_rate_xx_per_s : 0.0;
  const double eyy = active ? m.strain_rate_yy_per_s : 0.0;
  const std::size_t n = particles_.size();
  double* v = particles_.velocity.data();
  const double* x = particles_.position.data();
  for (std::size_t i = 0; i < n; ++i) {
    v[2 * i] = exx * (x[2 * i] - m.origin_x_m);
    v[2 * i + 1] = eyy * (x[2 * i + 1] - m.origin_y_m);
  }
}

void DemSystem::drift(double dt) {
  const std::size_t m = particles_.position.size();
  double* x = particles_.position.data();
  const double* v = particles_.velocity.data();
  for (std::size_t k = 0; k < m; ++k) x[k] += dt * v[k];
}

void DemSystem::compute_internal_forces() {
  internal_forces_current_ = true;
  const std::size_t n = particles_.size();
  double* f = particles_.force.data();
  const double* inv_m = particles_.inv_mass.data();
  for (std::size_t i = 0; i < n; ++i) {
    f[2 * i] = settings_.gravity_x_m_s2 / inv_m[i];
    f[2 * i + 1] = settings_.gravity_y_m_s2 / inv_m[i];
  }
}

void DemSystem::add_external_forces() {
  const std::size_t m = particles_.force.size();
  double* f = particles_.force.data();
  const double* fe = particles_.external_force.data();
  for (std::size_t k = 0; k < m; ++k) f[k] += fe[k];
}

void DemSystem::step(double dt) {
  begin_step(dt);
  compute_internal_forces();
  add_external_forces();
  if (!settings_.prescribed_motion) half_kick(dt);
  in_split_step_ = false;
}

void DemSystem::begin_step(double dt) {
  if (in_split_step_) throw std::logic_error("begin_step inside a split step");
  if (settings_.prescribed_motion) {
    set_prescribed_velocity(time_s_ + 0.5 * dt);  // v^{n+1/2} of the field
  } else {
    half_kick(dt);
  }
  drift(dt);
  time_s_ += dt;
  ++steps_;
  internal_forces_current_ = false;
  in_split_step_ = true;
}

void DemSystem::finish_step(double dt, std::span<const double> external) {
  if (!in_split_step_) throw std::logic_error("finish_step without begin_step");
  set_external_force(external);
  if (!settings_.prescribed_motion) half_kick(dt);
  in_split_step_ = false;
}

void DemSystem::set_external_force(std::span<const double> external) {
  if (external.size() != particles_.external_force.size()) {
    throw std::invalid_argument("external force has " + std::to_string(external.size()) +
                                " values for " + std::to_string(particles_.size()) + " particles");
  }
  std::copy(external.begin(), external.end(), particles_.external_force.begin());
  // At rest (t = 0) a^n is re-evaluated from scratch; inside a split step the internal forces at
  // x^{n+1} may already have been computed while the fluid worked.
  if (!in_split_step_ || !internal_forces_current_) compute_internal_forces();
  add_external_forces();
}

double DemSystem::kinetic_energy() const {
  const std::size_t n = particles_.size();
  double e = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double vx = particles_.velocity[2 * i];
    const double vy = particles_.velocity[2 * i + 1];
    e += 0.5 * (vx * vx + vy * vy) / particles_.inv_mass[i];
  }
  return e;
}

}  // namespace rockcut::dem
