// The external (fluid) force of DemSystem: held between exchanges, or extrapolated
// (core/fluid_force_extrapolation.hpp), with the lag's energy observer
// (core/fluid_force_passivity.hpp), the grain's own fluid stiffness
// (core/fluid_self_stiffness.hpp), and a membrane's dead load on top.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/dem_system.hpp"

namespace rockcut::dem {

void DemSystem::hold_external_force(std::span<const double> external) {
  if (external.size() != particles_.external_force.size()) {
    throw std::invalid_argument("external force has " + std::to_string(external.size()) +
                                " values for " + std::to_string(particles_.size()) + " particles");
  }
  std::copy(external.begin(), external.end(), particles_.external_force.begin());
  if (!has_body_forces_) {
    has_body_forces_ =
        std::any_of(external.begin(), external.end(), [](double f) { return f != 0.0; });
  }
  for (std::size_t k = 0; k < membrane_.particles.size(); ++k) {
    particles_.external_force[2 * membrane_.particles[k]] += membrane_.force_x_n_per_m[k];
  }
}

void DemSystem::add_membrane_load(MembraneLoad load) {
  membrane_ = std::move(load);
  has_body_forces_ = has_body_forces_ || !membrane_.particles.empty();  // its work is booked
  // The fluid's part of the held force stays; the membrane is added on top by the hold.
  std::vector<double> held = particles_.external_force;
  hold_and_reevaluate(held);
}

void DemSystem::extrapolate_external_force(bool on) {
  if (on == extrapolation_.on) return;
  extrapolation_ = FluidForceExtrapolation{};
  extrapolation_.on = on;
}

void DemSystem::set_external_force(std::span<const double> external,
                                   std::span<const double> self_stiffness_pa) {
  check_self_stiffness(self_stiffness_pa);
  hold_and_reevaluate(external);  // checks the size first: a refused force changes nothing
  extrapolation_.take(external, time_s_);
  self_stiffness_.take(self_stiffness_pa, particles_.position, time_s_, extrapolation_.rate);
  has_body_forces_ = has_body_forces_ || self_stiffness_.stiffens();  // its work is booked
  passivity_.exchange(particles_.position, particles_.external_force, particles_.inv_mass, dt_last_,
                      steps_);
}

void DemSystem::correct_lag_passively(bool on) {
  if (on == passivity_.on) return;
  passivity_ = FluidForcePassivity{};
  passivity_.on = on;
}

void DemSystem::stiffen_external_force(bool on) {
  if (on == self_stiffness_.on) return;
  self_stiffness_ = FluidSelfStiffness{};
  self_stiffness_.on = on;
}

void DemSystem::check_self_stiffness(std::span<const double> k) const {
  if (!self_stiffness_.on) return;
  if (k.size() != 3 * particles_.size()) {
    throw std::invalid_argument("fluid self stiffness has " + std::to_string(k.size()) +
                                " values for " + std::to_string(particles_.size()) +
                                " particles (3 each: xx, xy, yy)");
  }
}

void DemSystem::hold_and_reevaluate(std::span<const double> external) {
  hold_external_force(external);
  // At rest (t = 0) a^n is re-evaluated from scratch; inside a split step the internal forces at
  // x^{n+1} may already have been computed while the fluid worked.
  if (!in_split_step_ || !internal_forces_current_) compute_internal_forces();
  finish_forces(0.0);
}

}  // namespace rockcut::dem
