// A uniform cell grid over the particles' bounding box, rebuilt from scratch when asked (counting
// sort, no allocation once the buffers have grown). Used to find near pairs: bonds at installation,
// contacts at every neighbour-list rebuild.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace rockcut::dem {

class CellGrid {
 public:
  /// Bins the points (interleaved x, y) into square cells of side >= `cell_size_m`.
  void build(std::span<const double> position, double cell_size_m);

  /// Calls f(i, j) once for every unordered pair i != j in the same or adjacent cells.
  template <typename F>
  void for_each_near_pair(F&& f) const;

  /// Calls f(i, j) for every j > i in the same or adjacent cells as particle i.
  template <typename F>
  void for_each_neighbour_of(std::uint32_t i, F&& f) const;

 private:
  int cell_of(double x, double y) const;

  double x0_ = 0, y0_ = 0, inv_size_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> start_;    // nx*ny + 1 offsets into sorted_
  std::vector<std::uint32_t> sorted_;   // particle indices by cell
  std::vector<std::int32_t> cell_;      // cell of each particle
  std::span<const double> position_;
};

template <typename F>
void CellGrid::for_each_neighbour_of(std::uint32_t i, F&& f) const {
  const int c = cell_[i];
  const int cx = c % nx_, cy = c / nx_;
  for (int dy = -1; dy <= 1; ++dy) {
    const int yy = cy + dy;
    if (yy < 0 || yy >= ny_) continue;
    for (int dx = -1; dx <= 1; ++dx) {
      const int xx = cx + dx;
      if (xx < 0 || xx >= nx_) continue;
      const int cc = yy * nx_ + xx;
      for (std::uint32_t k = start_[cc]; k < start_[cc + 1]; ++k) {
        const std::uint32_t j = sorted_[k];
        if (j > i) f(i, j);
      }
    }
  }
}

template <typename F>
void CellGrid::for_each_near_pair(F&& f) const {
  const auto n = static_cast<std::uint32_t>(cell_.size());
  for (std::uint32_t i = 0; i < n; ++i) for_each_neighbour_of(i, f);
}

}  // namespace rockcut::dem
