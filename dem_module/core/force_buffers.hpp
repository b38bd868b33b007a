// Per-thread force accumulation for the pair loops. Thread 0 adds straight into the particle
// arrays; other threads into private buffers that are summed afterwards. No atomics, no races, and
// one thread pays nothing extra.
#pragma once

#include <vector>

#include "core/particles.hpp"

namespace rockcut::dem {

struct ForceView {
  double* force;   ///< interleaved x, y
  double* torque;
};

class ForceBuffers {
 public:
  /// Sizes the buffers for `threads` threads and n particles (allocates only when they grow).
  void resize(int threads, std::size_t n);
  /// Zeroes thread t's private buffer (t >= 1); each thread zeroes its own.
  void zero(int thread);
  ForceView view(int thread, Particles& p);
  /// Adds every private buffer into the particle arrays for particles [begin, end).
  void reduce(Particles& p, std::size_t begin, std::size_t end) const;
  int threads() const { return threads_; }

 private:
  int threads_ = 1;
  std::vector<std::vector<double>> force_, torque_;
};

}  // namespace rockcut::dem
