#include "sp/neighbours.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <omp.h>

namespace rockcut::fluid::sp {

NeighbourList::NeighbourList(double support_m, double skin)
    : radius_(support_m * (1.0 + skin)), half_skin_m_(0.5 * skin * support_m) {
  if (!(support_m > 0.0) || !(skin >= 0.0)) {
    throw std::invalid_argument("NeighbourList: support must be > 0 and skin >= 0");
  }
}

bool NeighbourList::update(std::span<const double> position) {
  if (position.size() != position_at_build_.size()) {
    build(position);
    return true;
  }
  const auto n = static_cast<std::ptrdiff_t>(position.size() / 2);
  const double* x = position.data();
  const double* x0 = position_at_build_.data();
  const double limit2 = half_skin_m_ * half_skin_m_;
  double max2 = 0.0;  // a maximum: the same at any thread count
#pragma omp parallel for schedule(static) reduction(max : max2)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const double dx = x[2 * i] - x0[2 * i], dy = x[2 * i + 1] - x0[2 * i + 1];
    max2 = std::max(max2, dx * dx + dy * dy);
  }
  // With no skin any motion at all invalidates the lists.
  if (half_skin_m_ > 0.0 ? max2 <= limit2 : max2 == 0.0) return false;
  build(position);
  return true;
}

void NeighbourList::bin(std::span<const double> position) {
  const std::size_t n = position.size() / 2;
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin;
  double xmax = -xmin, ymax = -xmin;
  for (std::size_t i = 0; i < n; ++i) {
    xmin = std::min(xmin, position[2 * i]);
    xmax = std::max(xmax, position[2 * i]);
    ymin = std::min(ymin, position[2 * i + 1]);
    ymax = std::max(ymax, position[2 * i + 1]);
  }
  if (!std::isfinite(xmin + xmax + ymin + ymax)) {
    throw std::runtime_error("fluid: a particle position is not finite");
  }
  // Cells at least as wide as the list radius (a 3 x 3 stencil then finds every pair); widened if
  // the particles are spread so thin that the grid would hold many more cells than particles.
  cell_m_ = radius_;
  const double max_cells = 4.0 * static_cast<double>(n) + 64.0;
  while (((xmax - xmin) / cell_m_ + 1.0) * ((ymax - ymin) / cell_m_ + 1.0) > max_cells) {
    cell_m_ *= 1.5;
  }
  x0_ = xmin;
  y0_ = ymin;
  nx_ = static_cast<int>((xmax - xmin) / cell_m_) + 1;
  ny_ = static_cast<int>((ymax - ymin) / cell_m_) + 1;

  // Counting sort of the particles by cell.
  cell_of_.resize(n);
  cell_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const int cx = std::min(nx_ - 1, static_cast<int>((position[2 * i] - x0_) / cell_m_));
    const int cy = std::min(ny_ - 1, static_cast<int>((position[2 * i + 1] - y0_) / cell_m_));
    cell_of_[i] = cy * nx_ + cx;
    ++cell_start_[cell_of_[i] + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_particles_.resize(n);
  cell_xy_.resize(2 * n);
  count_.assign(cell_start_.begin(), cell_start_.end() - 1);  // fill cursor per cell
  for (std::size_t i = 0; i < n; ++i) {
    const int slot = count_[cell_of_[i]]++;
    cell_particles_[slot] = static_cast<int>(i);
    cell_xy_[2 * slot] = position[2 * i];  // coordinates in cell order: contiguous candidates
    cell_xy_[2 * slot + 1] = position[2 * i + 1];
  }
}

void NeighbourList::build(std::span<const double> position) {
  const std::size_t n = position.size() / 2;
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max() / 64)) {
    throw std::invalid_argument("fluid: too many particles for 32-bit neighbour indices");
  }
  position_at_build_.assign(position.begin(), position.end());
  offsets_.assign(n + 1, 0);
  ++builds_;
  if (n == 0) {
    neighbours_.clear();
    return;
  }
  bin(position);
  const double* x = position.data();
  const double* cxy = cell_xy_.data();
  const double r2max = radius_ * radius_;

  // Candidates of particle i within the list radius, i itself included, cell by cell, written
  // into `out` without a branch per candidate (about a third of the candidates of a 3 x 3 block
  // are accepted, at random: a branch would be mispredicted half the time). Returns the count.
  auto candidates = [&](int i, int* out) {
    const double xi = x[2 * i], yi = x[2 * i + 1];
    const int c = cell_of_[i];
    const int cx = c % nx_, cy = c / nx_;
    int m = 0;
    for (int gy = std::max(0, cy - 1); gy <= std::min(ny_ - 1, cy + 1); ++gy) {
      const int g0 = gy * nx_ + std::max(0, cx - 1), g1 = gy * nx_ + std::min(nx_ - 1, cx + 1);
      for (int k = cell_start_[g0]; k < cell_start_[g1 + 1]; ++k) {  // adjacent cells: one run
        const double dx = cxy[2 * k] - xi, dy = cxy[2 * k + 1] - yi;
        out[m] = cell_particles_[k];
        m += dx * dx + dy * dy < r2max;
      }
    }
    return m;
  };
  int max_cell = 0;
  for (std::size_t c = 0; c + 1 < cell_start_.size(); ++c) {
    max_cell = std::max(max_cell, cell_start_[c + 1] - cell_start_[c]);
  }
  // One candidate buffer per thread of the model's team.
  const auto stride = static_cast<std::size_t>(9 * max_cell + 1);
  scratch_.resize(stride * static_cast<std::size_t>(omp_get_max_threads()));

  // Pass 1: row lengths; pass 2: rows. Particles are visited cell by cell, so the candidates of
  // consecutive particles are the same few cells, hot in cache, whatever the particle numbering.
  // Each row is written by one thread at offsets fixed by pass 1 and sorted: the same list at any
  // thread count.
  const int count = static_cast<int>(n);
#pragma omp parallel
  {
    int* tmp = scratch_.data() + stride * static_cast<std::size_t>(omp_get_thread_num());
#pragma omp for schedule(static)
    for (int k = 0; k < count; ++k) {
      const int i = cell_particles_[k];
      offsets_[i + 1] = candidates(i, tmp) - 1;  // without i itself
    }
  }
  // Outside the parallel regions: an allocation that fails throws to the caller.
  for (std::size_t i = 0; i < n; ++i) offsets_[i + 1] += offsets_[i];
  neighbours_.resize(static_cast<std::size_t>(offsets_[n]));
#pragma omp parallel
  {
    int* tmp = scratch_.data() + stride * static_cast<std::size_t>(omp_get_thread_num());
#pragma omp for schedule(static)
    for (int k = 0; k < count; ++k) {
      const int i = cell_particles_[k];
      const int m = candidates(i, tmp);
      int* row = neighbours_.data() + offsets_[i];
      int r = 0;
      for (int q = 0; q < m; ++q) {
        if (tmp[q] != i) row[r++] = tmp[q];
      }
      std::sort(row, row + r);
    }
  }
}

}  // namespace rockcut::fluid::sp
