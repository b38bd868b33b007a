#include "core/particles.hpp"

#include <numbers>

namespace rockcut::dem {

void Particles::add(double x, double y, double r, double rho) {
  position.insert(position.end(), {x, y});
  velocity.insert(velocity.end(), {0.0, 0.0});
  force.insert(force.end(), {0.0, 0.0});
  external_force.insert(external_force.end(), {0.0, 0.0});
  angular_velocity.push_back(0.0);
  torque.push_back(0.0);
  radius.push_back(r);
  const double mass = rho * std::numbers::pi * r * r;  // per metre of thickness
  inv_mass.push_back(1.0 / mass);
  inv_inertia.push_back(2.0 / (mass * r * r));  // I = m r^2 / 2 for a disc
}

}  // namespace rockcut::dem
