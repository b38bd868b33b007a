#include "core/force_buffers.hpp"

#include <algorithm>

namespace rockcut::dem {

void ForceBuffers::resize(int threads, std::size_t n) {
  force_.resize(threads > 1 ? threads - 1 : 0);
  torque_.resize(force_.size());
  for (std::size_t t = 0; t < force_.size(); ++t) {
    if (force_[t].size() != 2 * n) force_[t].assign(2 * n, 0.0);  // new buffers start at zero
    if (torque_[t].size() != n) torque_[t].assign(n, 0.0);
  }
}

ForceView ForceBuffers::view(int thread, Particles& p) {
  if (thread == 0) return {p.force.data(), p.torque.data()};
  return {force_[thread - 1].data(), torque_[thread - 1].data()};
}

void ForceBuffers::reduce(Particles& p, std::size_t begin, std::size_t end) {
  for (std::size_t t = 0; t < force_.size(); ++t) {
    double* f = force_[t].data();
    double* q = torque_[t].data();
    for (std::size_t i = begin; i < end; ++i) {
      p.force[2 * i] += f[2 * i];
      p.force[2 * i + 1] += f[2 * i + 1];
      p.torque[i] += q[i];
      // Zeroed here, by the thread that owns these particles, ready for the next evaluation: the
      // clearing is shared evenly instead of falling on the private buffers' threads.
      f[2 * i] = f[2 * i + 1] = 0.0;
      q[i] = 0.0;
    }
  }
}

}  // namespace rockcut::dem
