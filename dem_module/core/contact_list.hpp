// Unbonded neighbour pairs (a half list built from a cell grid with a Verlet skin) and their
// tangential spring history, which survives rebuilds. Contacts follow DESIGN section 4: normal
// k_n * overlap (compression only), incremental tangential force limited by mu * F_n.
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

class BondSet;
class CellGrid;

class ContactList {
 public:
  /// Lists every unbonded pair closer than r_i + r_j + skin, keeping the tangential force of pairs
  /// that were already listed.
  void rebuild(const Particles& p, const BondSet& bonds, double skin_m, CellGrid& grid);
  /// The same in parts, for a team of threads: begin_rebuild (one thread: the history sorted,
  /// the grid built), search (every thread t of `threads`: the pairs of its share of the
  /// particles, into its own buffer), size_join (one thread: the list sized, each thread's
  /// offset), join (every thread t: its pairs copied to its offset). The list comes out in the
  /// order of a search on one thread, at any thread count.
  void begin_rebuild(const Particles& p, double skin_m, CellGrid& grid, int threads);
  void search(const Particles& p, const BondSet& bonds, double skin_m, const CellGrid& grid,
              int t, int threads);
  void size_join();
  void join(int t);
  /// Adds the pairs of freshly broken bonds (interleaved i, j): they may collide from now on.
  void add_pairs(const std::vector<std::uint32_t>& pairs);

  /// Adds contact forces for pairs [begin, end) into `out`, and what friction, the dashpots
  /// (law.damping_ratio) and the rolling springs (law.rolling_friction) dissipate into `sums`.
  void compute(const Particles& p, const ContactLaw& law, double dt, std::size_t begin,
               std::size_t end, ForceView out, ContactDissipation& sums);
  /// Elastic energy in the active contacts [J/m].
  double strain_energy(const Particles& p, const ContactLaw& law) const;

  std::size_t size() const { return i_.size(); }
  /// Checkpoint (core/dem_state.cpp): the pairs in list order, their tangential history and
  /// their dashpots' last forces.
  void save_state(state::StateArchive& a) const;
  void load_state(const state::StateArchive& a, std::size_t particles);
  std::uint32_t first(std::size_t k) const { return i_[k]; }
  std::uint32_t second(std::size_t k) const { return j_[k]; }

 private:
  template <bool kDashpots, bool kRolling>
  void compute_impl(const Particles& p, const ContactLaw& law, double dt, std::size_t begin,
                    std::size_t end, ForceView out, ContactDissipation& sums);

  std::vector<std::uint32_t> i_, j_;
  std::vector<double> shear_force_;  ///< along t = (-n_y, n_x), acting on j [N/m]
  std::vector<double> rolling_moment_;  ///< rolling spring's moment on i [N m/m] (0 without)
  /// The dashpots' forces of the last evaluation (the F^n end of their trapezoid; 0 without).
  std::vector<PairDashpots> dashpot_;
  // Rebuild scratch, kept to avoid allocating in steady state. The tangential history of the
  // listed pairs, sorted by pair for the search's lookups.
  struct History {
    std::uint64_t key;
    double shear, rolling;
    PairDashpots dashpot;
  };
  std::vector<History> history_;
  struct Found {  // one thread's pairs in search()
    std::vector<std::uint32_t> i, j;
    std::vector<double> shear, rolling;
    std::vector<PairDashpots> dashpot;
  };
  std::vector<Found> found_;
  std::vector<std::size_t> offset_;  // where each thread's pairs go in the joined list
};

}  // namespace rockcut::dem
