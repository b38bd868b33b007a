// Per-thread force accumulation for the pair loops, split by ownership. Thread t owns the particles
// of its static share and adds their forces straight into the particle arrays; a pair's share for a
// particle another thread owns goes into t's own buffer instead. Those foreign entries lie near the
// shares' borders (the particles are numbered in cell order), so the reduction afterwards only
// walks each buffer's window of touched entries. No atomics, no races, and one thread pays nothing
// extra.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/particles.hpp"

namespace rockcut::dem {

struct ForceView {
  double* force;         ///< the particle arrays (interleaved x, y) for owned particles
  double* torque;
  double* other_force;   ///< this thread's buffer for particles other threads own
  double* other_torque;
  std::size_t own_begin = 0, own_count = 0;  ///< the owned particles [own_begin, own_begin + own_count)

  bool owns(std::uint32_t i) const { return std::size_t(i) - own_begin < own_count; }  // wraps below

  /// Adds force (fx, fy) and moment q to particle i: into the particle arrays if this thread
  /// owns it, into this thread's buffer if not.
  void add(std::uint32_t i, double fx, double fy, double q) const {
    const bool own = owns(i);
    double* f = own ? force : other_force;
    f[2 * i] += fx;
    f[2 * i + 1] += fy;
    (own ? torque : other_torque)[i] += q;
  }
  /// A pair's forces: (fx, fy) on j, its opposite on i, and the moments q_i, q_j.
  void add_pair(std::uint32_t i, std::uint32_t j, double fx, double fy, double q_i,
                double q_j) const {
    add(i, -fx, -fy, q_i);
    add(j, fx, fy, q_j);
  }
};

class ForceBuffers {
 public:
  /// Sizes the buffers for `threads` threads and n particles; new buffers are zero, and reduce()
  /// leaves them zero again (allocates only when the size changes).
  void resize(int threads, std::size_t n);
  /// The view of thread t, which owns particles [own_begin, own_end).
  ForceView view(int thread, Particles& p, std::size_t own_begin, std::size_t own_end);
  /// Sets the window [begin, end) of foreign particles that thread t's pairs touch; reduce() reads
  /// only these entries. Called whenever the pair lists or their shares change.
  void set_window(int thread, std::size_t begin, std::size_t end);
  /// Adds the other threads' buffers into the particle arrays for the owned particles
  /// [begin, end) of thread t, and zeroes those buffer entries.
  void reduce(Particles& p, int thread, std::size_t begin, std::size_t end);

 private:
  std::vector<std::vector<double>> force_, torque_;
  std::vector<std::size_t> window_begin_, window_end_;
};

}  // namespace rockcut::dem
