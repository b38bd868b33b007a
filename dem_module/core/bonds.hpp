// Bonds between neighbouring discs (paper section 3.1, figure 4; DESIGN section 4): linear elastic
// and perfectly brittle, in structure-of-arrays form. The list changes only when bonds break.
#pragma once

#include <cstdint>
#include <vector>

#include "core/energy.hpp"
#include "core/force_buffers.hpp"
#include "core/interaction_law.hpp"
#include "core/particles.hpp"
#include "core/viscous_damping.hpp"
#include "wire/state_archive.hpp"

namespace rockcut::dem {

class CellGrid;

class BondSet {
 public:
  BondSet() = default;
  /// Bonds every pair whose surface gap is at most `gap_tolerance_m`, with rest length the current
  /// distance (so the specimen starts unstressed).
  static BondSet install(const Particles& p, const BondLaw& law, double gap_tolerance_m,
                         CellGrid& grid);

  std::size_t size() const { return i_.size(); }
  const BondLaw& law() const { return law_; }

  /// Adds the bond forces at the current positions (and velocities, for the incremental shear) into
  /// `out` for bonds [begin, end). A bond whose strength is exceeded breaks now and carries no
  /// force: it is flagged, and remove_broken() records it. A pair that breaks while its discs
  /// overlap gets, in this same evaluation, the normal force of the contact that replaces the bond,
  /// contact_normal_pa times the overlap (0 without contacts). With
  /// damping_ratio > 0 each bond has a normal and a tangential dashpot beside its springs
  /// (core/viscous_damping.hpp), whose dissipation is added to `viscous_j`. With a softening law
  /// (softening_ratio > 0) a bond past its strength softens (core/bond_softening.hpp) and breaks
  /// when its damage reaches 1; what softening dissipates is added to `softening_j`.
  void compute(const Particles& p, double dt, std::size_t begin, std::size_t end, ForceView out,
               bool& any_broken, double contact_normal_pa, double damping_ratio,
               double& viscous_j, double& softening_j);
  /// Removes the flagged bonds, appending their breaks (and the pairs, which may now collide) to
  /// the given lists, and the elastic energy they released to the ledger (bond_energy_released,
  /// core/bond_law.hpp: less what the contact spring of a compressed pair keeps).
  void remove_broken(const Particles& p, double time_s, std::vector<BondBreak>& breaks,
                     std::vector<std::uint32_t>& freed_pairs, EnergyLedger& ledger);

  /// Elastic energy stored in the bonds at the current positions [J/m].
  double strain_energy(const Particles& p) const;
  /// Bonds per particle (for damage D = 1 - bonds / initial bonds).
  void count_per_particle(std::size_t n, std::vector<std::uint32_t>& count) const;
  /// True if i and j are bonded; needs partners() to be current (refresh_partners()).
  bool bonded(std::uint32_t i, std::uint32_t j) const;
  void refresh_partners(std::size_t n);
  /// Checkpoint (core/dem_state.cpp): the bonds, their springs, dashpots' last forces and broken
  /// flags; loaded onto the particles `p` (their count and masses).
  void save_state(state::StateArchive& a) const;
  void load_state(const state::StateArchive& a, const Particles& p);

  // Test access.
  /// Normal force of bond k at the current positions (compression positive) [N/m].
  double normal_force(std::size_t k, const Particles& p) const;
  double shear_force(std::size_t k) const { return shear_force_[k]; }
  /// D of bond k (0 under the brittle law).
  double damage(std::size_t k) const { return damage_.empty() ? 0.0 : damage_[k]; }
  std::uint32_t first(std::size_t k) const { return i_[k]; }
  std::uint32_t second(std::size_t k) const { return j_[k]; }

 private:
  /// A pair's geometry as compute_impl formed it, for the cold paths, with its length before the
  /// drift into this evaluation.
  struct PairGeometry {
    std::uint32_t i, j;
    double length_m, nx, ny;      ///< now, and the unit normal from i to j
    double rel_vx, rel_vy;        ///< v_j - v_i at the half step
    double length_before_m;       ///< at x^n = x^{n+1} - v^{n+1/2} dt
  };
  PairGeometry geometry_again(std::size_t k, const Particles& p, double dt) const;
  /// The length of bond k's pair at the current positions [m].
  double length_m(std::size_t k, const Particles& p) const;
  /// sqrt(m_eff) of every bond's pair, which its dashpots scale with: computed once from the
  /// masses (which never change) instead of at every step, by install() and load_state().
  void refresh_pair_masses(const Particles& p);

  template <bool kDashpots, bool kSoftening>
  void compute_impl(const Particles& p, double dt, std::size_t begin, std::size_t end,
                    ForceView out, bool& any_broken, double contact_normal_pa,
                    double damping_ratio, double& viscous_j, double& softening_j);

  /// Bond k breaks in this evaluation (at F_n `fn`, trial shear `fs`, shear strength `ts_fn`):
  /// flagged, its release and its dashpots' last work booked, the contact's normal force of a
  /// pressed pair added. Out of the pair loop (cold): inlined, it slowed every bond's step.
  template <bool kDashpots>
  [[gnu::cold, gnu::noinline]] void break_now(std::size_t k, const Particles& p, double dt,
                                              double fn, double fs, double ts_fn, ForceView out,
                                              double contact_normal_pa, double& dissipated_j);
  /// Bond k is damaged or past its strength under a softening law: its damage, forces and
  /// dashpots for this evaluation (core/bond_softening.hpp), the softening's dissipation added to
  /// `softening_j`. Returns true if it breaks (damage 1), booked as break_now books a break.
  /// Out of the pair loop: only the bonds in a process zone come here.
  template <bool kDashpots>
  [[gnu::noinline]] bool soften(std::size_t k, const Particles& p, double dt, double fn, double fs,
                                ForceView out, double contact_normal_pa, double cn_scale,
                                double ct_scale, double& dissipated_j, double& softening_j);

  BondLaw law_;
  std::vector<std::uint32_t> i_, j_;
  std::vector<double> rest_length_;
  std::vector<double> shear_force_;   ///< F_t along t = (-n_y, n_x), acting on j [N/m]
  std::vector<double> released_at_break_;  ///< energy a bond released as it broke [J/m]
  /// The dashpots' forces of the last evaluation (the F^n end of their trapezoid; 0 without).
  std::vector<PairDashpots> dashpot_;
  std::vector<double> sqrt_mass_;     ///< sqrt_effective_mass of the pair [sqrt(kg/m)]
  std::vector<std::uint8_t> broken_;  ///< 0, or 1 + BreakMode
  /// D of a softening bond (core/bond_softening.hpp); empty under the brittle law.
  std::vector<double> damage_;
  std::vector<std::uint8_t> damaged_;  ///< damage_[k] > 0, for the hot loop's check
  std::vector<std::uint32_t> partner_start_, partner_;
};

}  // namespace rockcut::dem
