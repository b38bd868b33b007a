// Neighbour lists of the SP operators, owned by the fluid module (it shares no code with the DEM).
//
// Every pair closer than the list radius h (1 + skin) is stored in compressed rows (CSR), both
// directions, each row sorted by neighbour index, so that per-particle sums need no atomics and
// the implicit model's sparse matrix has the same pattern. Built with a cell list in O(N); rebuilt
// only when some particle has moved more than half the skin since the last build, because until
// then no pair can have come closer than h unseen (each of the two moved at most skin / 2).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rockcut::fluid::sp {

class NeighbourList {
 public:
  /// support_m: the kernel support h [m]; skin: extra list radius as a fraction of h.
  NeighbourList(double support_m, double skin);

  /// Rebuilds the lists if a particle has moved more than half the skin since the last build, or
  /// if the particle count changed. `position` is interleaved x, y [m]. Returns true if it rebuilt.
  bool update(std::span<const double> position);
  /// Rebuilds unconditionally.
  void build(std::span<const double> position);

  std::size_t particles() const { return offsets_.empty() ? 0 : offsets_.size() - 1; }
  /// Row i holds neighbours()[offsets()[i] .. offsets()[i + 1]), sorted, never i itself.
  const std::vector<int>& offsets() const { return offsets_; }
  const std::vector<int>& neighbours() const { return neighbours_; }
  std::size_t pairs() const { return neighbours_.size(); }
  std::uint64_t builds() const { return builds_; }
  double list_radius_m() const { return radius_; }
  /// The positions of the last build: a checkpoint rebuilds the same lists from them.
  const std::vector<double>& position_at_build() const { return position_at_build_; }
  /// Builds from `position_at_build` and takes `builds` as the count of builds so far (restart).
  void restore(std::span<const double> position_at_build, std::uint64_t builds) {
    build(position_at_build);
    builds_ = builds;
  }

 private:
  void bin(std::span<const double> position);

  double radius_;       // h (1 + skin)
  double half_skin_m_;  // rebuild threshold on the displacement since the last build
  std::vector<int> offsets_, neighbours_;
  std::vector<double> position_at_build_;
  std::uint64_t builds_ = 0;

  // Cell list (reused between builds: no allocation once sizes settle).
  double cell_m_ = 0, x0_ = 0, y0_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<int> cell_of_, cell_start_, cell_particles_, count_;
  std::vector<double> cell_xy_;  // positions in cell order
  std::vector<int> scratch_;     // candidates of one particle, one buffer per thread
};

}  // namespace rockcut::fluid::sp
