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
  /// Sizes the buffers for `threads` threads and n particles; new buffers are zero, and reduce()
  /// leaves them zero again (allocates only when the size changes).
  void resize(int threads, std::size_t n);
  ForceView view(int thread, Particles& p);
  /// Adds every private buffer into the particle arrays for particles [begin, end), and zeroes
  /// those buffer entries.
  void reduce(Particles& p, std::size_t begin, std::size_t end);

 private:
  std::vector<std::vector<double>> force_, torque_;
};

}  // namespace rockcut::dem
