// The DEM state and its time integration: velocity Verlet with rotation, paper eqs. 5-8 (eq. 8's
// v^{i+1/2} is v^{n+1/2}), split in two halves so the fluid can act between them (DESIGN section 3).
// Forces at x^{n+1} use v^{n+1/2} (the paper's remark under eq. 8).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/bonds.hpp"
#include "core/cell_grid.hpp"
#include "core/contact_list.hpp"
#include "core/energy.hpp"
#include "core/fluid_force_extrapolation.hpp"
#include "core/fluid_force_passivity.hpp"
#include "core/fluid_self_stiffness.hpp"
#include "core/force_buffers.hpp"
#include "core/particles.hpp"
#include "wire/phase_clock.hpp"
#include "core/membrane_load.hpp"
#include "core/wall_servo.hpp"
#include "core/walls.hpp"

namespace rockcut::dem {

/// A uniform deformation that replaces Newton's law (fluid-only verification scenes):
/// v = diag(exx, eyy) (x - origin) for start <= t < end, else 0.
struct PrescribedMotion {
  double strain_rate_xx_per_s = 0.0;
  double strain_rate_yy_per_s = 0.0;
  double origin_x_m = 0.0, origin_y_m = 0.0;
  double start_time_s = 0.0;
  double end_time_s = 1e300;
};

struct DemSettings {
  double gravity_x_m_s2 = 0.0;
  double gravity_y_m_s2 = 0.0;
  /// All-zero stiffness: discs pass through each other (no contacts). Its damping_ratio is that of
  /// every dashpot, the bonds' too (core/viscous_damping.hpp).
  ContactLaw contact;
  double local_damping = 0.0;  ///< alpha_d of eq. 10 (Potyondy & Cundall 2004); 0: none
  double skin_m = 0.0;         ///< Verlet skin of the neighbour list; 0: chosen from the radii
  int threads = 1;             ///< OpenMP threads of the pair loops
  std::optional<PrescribedMotion> prescribed_motion;
};

/// Discs whose vertical motion is prescribed (the clamped end layers of a UCS specimen): their y
/// velocity is held at velocity_y_m_s, x and rotation stay free. The force that holds them is the
/// reaction.
struct ClampedGroup {
  std::vector<std::uint32_t> particles;
  double velocity_y_m_s = 0.0;
  bool fixed = false;  ///< held in x and spin too, at rest (add_clamped_group)
  double reaction_y_n_per_m = 0.0;  ///< sum of the internal y forces on the group at the last step
};

/// What one thread sums over its share of a pass; combined in thread order afterwards, so the
/// same thread count gives the same bits. A cache line each, so the threads do not share one.
struct alignas(64) ThreadSums {
  double vmax2 = 0.0;  ///< largest v^2 [m^2/s^2]
  double external_work_j = 0.0, gravity_work_j = 0.0, damping_j = 0.0, lag_correction_j = 0.0;
  ContactDissipation pairs;  ///< friction, dashpots, rolling springs
  double bond_viscous_j = 0.0;  ///< the part of pairs.viscous_j taken by the bonds' dashpots
  double bond_softening_j = 0.0;  ///< dissipated by softening bonds
  bool any_broken = false;
};

class DemSystem {
 public:
  DemSystem(Particles particles, const DemSettings& settings, BondSet bonds = {},
            WallSet walls = {});

  /// One full step of dt [s]: half kick, drift, forces at x^{n+1}, half kick.
  void step(double dt);
  /// First half of a step: v^{n+1/2} = v^n + a^n dt/2 (eq. 6), x^{n+1} = x^n + v^{n+1/2} dt (eq. 5).
  void begin_step(double dt);
  /// Internal forces at x^{n+1}. They do not depend on the fluid, so the module computes them while
  /// the fluid works; finish_step computes them itself if that has not happened.
  void compute_internal_forces();
  /// Second half: total force = internal + `external` (eq. 7), v^{n+1} = v^{n+1/2} + a dt/2 (eq. 8).
  /// `external` (2 per particle, [N/m]) is held for later steps until replaced.
  /// `self_stiffness_pa`: the fluid's K_ii at this exchange, 3 per particle, where the run
  /// applies it (stiffen_external_force); otherwise empty.
  void finish_step(double dt, std::span<const double> external,
                   std::span<const double> self_stiffness_pa = {});
  /// Replaces the held external force and re-evaluates a^n without moving (used at t = 0).
  void set_external_force(std::span<const double> external,
                          std::span<const double> self_stiffness_pa = {});
  /// From the next external force on, extrapolate it between exchanges instead of holding it
  /// (core/fluid_force_extrapolation.hpp); off: hold it (and drop the rate).
  void extrapolate_external_force(bool on);
  bool external_force_extrapolated() const { return extrapolation_.on; }
  /// From the next exchange on, take out the energy the lag between exchanges generates
  /// (core/fluid_force_passivity.hpp); off: drop the observer.
  void correct_lag_passively(bool on);
  const FluidForcePassivity& lag_passivity() const { return passivity_; }
  /// From the next exchange on, add to the external force each grain's own fluid stiffness
  /// against its motion since the exchange (core/fluid_self_stiffness.hpp); off: drop it.
  void stiffen_external_force(bool on);
  const FluidSelfStiffness& fluid_self_stiffness() const { return self_stiffness_; }
  /// Holds the y velocity of `particles` at velocity_y_m_s from now on (dry scenes: an external y
  /// force on them is cancelled too). Returns the group's index for clamped_group().
  /// `fixed`: held at rest in x and spin too (velocity_y_m_s 0), the rock mass under a cut block.
  std::size_t add_clamped_group(std::vector<std::uint32_t> particles, double velocity_y_m_s,
                                bool fixed = false);
  const ClampedGroup& clamped_group(std::size_t k) const { return clamped_[k]; }
  /// Steers a wall by `servo` at the end of every step from now on (a biaxial test's side walls).
  /// Stateless beyond the wall's velocity, which the checkpoint holds.
  void add_wall_servo(const WallServo& servo) { servos_.push_back(servo); }
  /// Adds a membrane's dead load (a biaxial test's confinement) to the held external force from
  /// now on, on top of any fluid force, and re-evaluates a^n (call at t = 0).
  void add_membrane_load(MembraneLoad load);
  const MembraneLoad& membrane_load() const { return membrane_; }

  const Particles& particles() const { return particles_; }
  /// For tests and drivers that set velocities between steps (a driven pair reversing).
  Particles& particles_for_driving() { return particles_; }
  const BondSet& bonds() const { return bonds_; }
  const WallSet& walls() const { return walls_; }
  const ContactList& contacts() const { return contacts_; }
  const std::vector<BondBreak>& breaks() const { return breaks_; }
  const EnergyLedger& ledger() const { return ledger_; }
  double time_s() const { return time_s_; }
  std::uint64_t step_count() const { return steps_; }
  bool in_split_step() const { return in_split_step_; }
  bool internal_forces_current() const { return internal_forces_current_; }
  std::uint64_t neighbour_rebuilds() const { return rebuilds_; }
  /// Wall time per phase of the step (DemPhase order), measured on the first thread.
  const wire::PhaseClock& phases() const { return phases_; }
  /// Checkpoint (core/dem_state.cpp): everything that decides the next bit, between two steps.
  void save_state(state::StateArchive& a) const;
  /// Restores a saved state into a system built from the same scene; throws state::StateError
  /// if it does not fit (another particle count, wall or clamp layout), and then leaves the
  /// system exactly as it was.
  void load_state(const state::StateArchive& a);

  /// Kinetic energy, translation and rotation [J/m].
  double kinetic_energy() const;
  /// Elastic energy in bonds and contacts [J/m].
  double strain_energy() const;

 private:
  /// load_state's work on this object; may throw with the object half-assigned (load_state runs it
  /// on a copy).
  void assign_state(const state::StateArchive& a);
  /// A whole step in one parallel region (step() when no motion is prescribed).
  void full_step(double dt);
  /// Eq. 6 (if `kick`) and eq. 5 in one pass; adds the F^n halves of the work trapezoids.
  void kick_drift(double dt, bool kick);
  // The per-particle passes on [begin, end), shared by the split step and full_step().
  /// Eqs. 6 and 5; with reset_forces the force then restarts from gravity.
  void drift_range(std::size_t begin, std::size_t end, double dt, bool kick, bool reset_forces,
                   ThreadSums& sums);
  void reset_forces_range(std::size_t begin, std::size_t end);
  // Without gravity a disc's weight gx / m^-1 is exactly +0 and its work adds +-0 to a sum that
  // starts at +0: the per-disc passes skip those divisions (two to four a disc and step) with the
  // same bits.
  bool has_gravity() const {
    return settings_.gravity_x_m_s2 != 0.0 || settings_.gravity_y_m_s2 != 0.0;
  }
  /// Thread t's share of the bonds and contacts, into its force view; thread 0 adds the walls.
  void pair_forces(int t, int threads, double dt, ThreadSums& sums);
  /// See finish_forces().
  void finish_range(std::size_t begin, std::size_t end, double kick_dt, ThreadSums& sums);
  void start_sums(int threads);
  ThreadSums total_sums() const;
  /// Adds the work, damping and friction terms of `s` to the ledger.
  void book(const ThreadSums& s);
  void remove_broken_bonds();
  /// Prescribed motion: the velocity of the field at the mid-step time t (replaces the kicks).
  void set_prescribed_velocity(double t);
  /// total force = internal + external, then local damping (eq. 10); accumulates work terms;
  /// with kick_dt > 0 also the second half kick (eq. 8) in the same pass.
  void finish_forces(double kick_dt);
  /// Copies the fluid force into the held external force, and adds the membrane's load on top.
  void hold_external_force(std::span<const double> external);
  /// Refuses a K_ii array of the wrong size while the self stiffness is on (before any change).
  void check_self_stiffness(std::span<const double> k) const;
  /// Holds `external` and re-evaluates a^n without moving.
  void hold_and_reevaluate(std::span<const double> external);
  void rebuild_neighbours();
  /// The same, called by every thread t of a team of `threads` (inside a parallel region): the
  /// contact search and the force windows shared out, the rest on one thread.
  void rebuild_neighbours_in_team(int t, int threads);
  /// Thread t's window of particles its pair loops touch outside its own share (ForceBuffers).
  void force_window(int t, int threads);
  /// Sizes the force buffers and sets each thread's window of foreign particles from its share of
  /// the pair lists: after every change of the lists (rebuild, removed bonds).
  void update_force_windows();
  /// Takes the internal y force off the clamped discs into their groups' reactions and books the
  /// work the clamps do (trapezoid over the step) as boundary work.
  void hold_clamped_groups();
  /// v_y of the clamped discs back to the prescribed value after a kick, and their y force to 0.
  void reset_clamped_velocities();
  /// Each servo-controlled wall's velocity for the next step from the forces of this one.
  void steer_servo_walls();

  Particles particles_;
  DemSettings settings_;
  BondSet bonds_;
  WallSet walls_;
  ContactList contacts_;
  CellGrid grid_;
  ForceBuffers buffers_;
  EnergyLedger ledger_;
  std::vector<BondBreak> breaks_;
  std::vector<std::uint32_t> freed_pairs_;
  std::vector<double> damping_force_;  ///< F_d of the last evaluation, 3 per particle (x, y, moment)
  FluidForceExtrapolation extrapolation_;  ///< the external force's rate between exchanges
  FluidForcePassivity passivity_;          ///< the lag's energy observer and dashpot
  FluidSelfStiffness self_stiffness_;      ///< the grain's own fluid stiffness between exchanges
  std::vector<ClampedGroup> clamped_;
  std::vector<WallServo> servos_;
  MembraneLoad membrane_;
  std::vector<ThreadSums> sums_;  ///< one per thread, for the pass in progress
  double max_drift_m_ = 0.0;  ///< bound on any disc's displacement since the last rebuild
  double dt_last_ = 0.0;
  double time_s_ = 0.0;
  std::uint64_t steps_ = 0;
  std::uint64_t rebuilds_ = 0;
  // Indices into phases_: drift (and the force reset), neighbour-list rebuilds, the three pair
  // loops, the wait for the slowest thread after them, reduction and kick, bond breaks.
  enum DemPhase : std::size_t {
    kDrift, kNeighbours, kBonds, kContacts, kWalls, kBarrier, kFinish, kBreaks
  };
  wire::PhaseClock phases_{
      {"drift", "neighbours", "bonds", "contacts", "walls", "barrier", "finish", "breaks"}};
  bool in_split_step_ = false;
  bool internal_forces_current_ = false;  // force holds the internal forces at x^{n+1}
  bool has_pairs_ = false;                // any contact law, bonds or walls at all
  bool has_body_forces_ = false;          // gravity or a non-zero external force: track its work
};

}  // namespace rockcut::dem
