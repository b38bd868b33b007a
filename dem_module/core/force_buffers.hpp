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
  /// Sizes the buffers for `threads` threads and n particles, zeroing the private ones.
  void prepare(int threads, std::size_t n);
  ForceView view(int thread, Particles& p);
  /// Adds every private buffer into the particle arrays.
  void reduce(Particles& p);
  int threads() const { return threads_; }

 private:
  int threads_ = 1;
  std::vector<std::vector<double>> force_, torque_;
};

}  // namespace rockcut::dem
