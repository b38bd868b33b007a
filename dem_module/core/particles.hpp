// Particle state as structure of arrays: the step loop streams through each array once.
// 2-component quantities are interleaved (x0, y0, x1, y1, ...) so they cross the wire as one copy.
// 2D discs of unit thickness: masses, forces and energies are per metre of thickness (DESIGN
// section 4): mass rho pi r^2, moment of inertia m r^2 / 2.
#pragma once

#include <cstddef>
#include <vector>

namespace rockcut::dem {

struct Particles {
  std::vector<double> position;        ///< [m], 2 per particle
  std::vector<double> velocity;        ///< [m/s], 2 per particle (v^{n+1/2} inside a split step)
  std::vector<double> force;           ///< [N/m], 2 per particle: total force of the last evaluation
  std::vector<double> external_force;  ///< [N/m], 2 per particle: held force from the fluid
  std::vector<double> angular_velocity;  ///< [rad/s]
  std::vector<double> torque;          ///< [N m/m]
  std::vector<double> radius;          ///< [m]
  std::vector<double> inv_mass;        ///< [m/kg] (1 / mass per metre of thickness)
  std::vector<double> inv_inertia;     ///< [m/(kg m^2)]

  std::size_t size() const { return radius.size(); }

  /// Appends a disc of radius r [m] and density rho [kg/m^3] at rest at (x, y).
  void add(double x, double y, double r, double rho);
};

}  // namespace rockcut::dem
