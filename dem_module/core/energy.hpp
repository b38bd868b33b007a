// Energy bookkeeping for the budget of DESIGN section 5 (per metre of thickness):
//   work in (walls, tool, external force, gravity) = kinetic + strain + damping + friction
//                                                     + energy of broken bonds + dashpots
//                                                     + rolling resistance.
// The step loop adds to these with OpenMP reductions; nothing is computed that is not asked for
// elsewhere.
#pragma once

namespace rockcut::dem {

struct EnergyLedger {
  double boundary_work_j = 0.0;   ///< done by walls and the tool on the particles
  double external_work_j = 0.0;   ///< done by the external (fluid) force
  double gravity_work_j = 0.0;    ///< done by gravity
  double damping_j = 0.0;         ///< dissipated by local damping (>= 0)
  double friction_j = 0.0;        ///< dissipated by sliding contacts (>= 0)
  double broken_bond_j = 0.0;     ///< taken by breaking bonds: released at the breaks (less what a
                                  ///< contact keeps) and dissipated by softening
  double viscous_damping_j = 0.0; ///< dissipated by the dashpots (>= 0)
  double rolling_j = 0.0;         ///< dissipated by rolling springs cut to their limit (>= 0)
  /// Taken out by the coupling lag's dashpot (core/fluid_force_passivity.hpp, >= 0).
  double lag_correction_j = 0.0;
  /// The part of viscous_damping_j taken by the bonds' dashpots: the intact rock's vibration.
  /// The rest is the contacts' and the walls' (collisions of loose discs and chips).
  double viscous_damping_bonds_j = 0.0;
  /// The part of broken_bond_j the softening bonds took on their way to breaking
  /// (core/bond_softening.hpp); the rest was released at the breaks.
  double bond_softening_j = 0.0;
};

/// What a pass over contacts dissipates [J/m], summed per thread.
struct ContactDissipation {
  double friction_j = 0.0;
  double viscous_j = 0.0;
  double rolling_j = 0.0;
};

}  // namespace rockcut::dem
