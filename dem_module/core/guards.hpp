// Runtime guards (DESIGN section 5): checks that stop a run whose state is no longer physical
// before it runs on to nonsense. They run once per report (every exchange or output step), never
// inside the step loop: each is one pass over the particles, bonds and contacts.
//
//   nan             a position, velocity, force or torque is NaN or Inf;
//   kinetic_energy  runaway kinetic energy: the kinetic energy, or the net work of the external
//                   (fluid) force, exceeds `kinetic_energy_factor` times all the energy the run was
//                   given (initial kinetic + strain energy, work of the walls, the tool and
//                   gravity; energy conservation allows at most 1: the pore fluid only stores and
//                   dissipates what the grains do on it), or a disc moves so fast that a head-on collision at that speed would overlap
//                   by more than the overlap limit: |v| > max_overlap_ratio R_min / t_c with t_c the
//                   smallest sqrt(m / k) (the DEM's critical time);
//   overlap         two discs (bonded or not), or a disc and a wall, overlap by more than
//                   `max_overlap_ratio` of the smaller radius: the linear contact law and the contact
//                   detection assume overlaps of a few per cent.
#pragma once

#include <cstdint>
#include <string>

#include "core/dem_system.hpp"

namespace rockcut::dem {

struct GuardLimits {
  bool enabled = true;
  double max_overlap_ratio = 0.25;      ///< overlap / smaller radius; 0: no overlap guard
  double kinetic_energy_factor = 1.5;   ///< kinetic / supplied energy; 0: no energy guard
  double critical_time_s = 0.0;         ///< smallest sqrt(m / k); 0: no speed guard
  /// The external force is a prescribed field (counted as given, like gravity), not a pore fluid.
  bool external_force_supplies_energy = false;
  // Derived once from the particles (make_guard_limits): fixed for a run.
  double r_min_m = 0.0;                 ///< smallest radius
  double speed_limit_m_s = 0.0;         ///< max_overlap_ratio r_min / t_c; 0: no speed guard
  /// Kinetic energy below which the energy guard never trips: the whole mass at 1e-3 of the speed
  /// limit (1 mm/s without one), so that a run given no energy yet cannot trip on round-off.
  double kinetic_energy_floor_j = 0.0;
};

/// The limits of a run of these particles, with the derived values filled in.
GuardLimits make_guard_limits(const Particles& p, double critical_time_s, double max_overlap_ratio,
                              double kinetic_energy_factor);

struct GuardFinding {
  std::string guard;     ///< empty: all guards passed
  std::string message;
  std::int64_t particle = -1;
  double x_m = 0.0, y_m = 0.0;
  double value = 0.0, limit = 0.0;
  bool tripped() const { return !guard.empty(); }
};

/// Largest overlap of any disc pair (bonded or in contact) or disc and wall, as a ratio of the
/// smaller radius, and a particle involved.
struct OverlapExtreme {
  double ratio = 0.0;
  std::int64_t particle = -1;
};
OverlapExtreme largest_overlap(const DemSystem& system);

/// Energy the run has been given so far [J/m]: `initial_energy_j` plus the positive work of the
/// walls, the tool and gravity, and of the external force if it is a prescribed field.
double energy_supplied_j(const DemSystem& system, double initial_energy_j,
                         bool external_force_supplies_energy);

/// Runs the guards in the order nan, kinetic_energy, overlap; returns the first that trips.
/// `kinetic_energy_j` is the current kinetic energy (computed by the caller for its report).
GuardFinding check_guards(const DemSystem& system, const GuardLimits& limits,
                          double initial_energy_j, double kinetic_energy_j);

}  // namespace rockcut::dem
