#include "core/force_buffers.hpp"

#include <algorithm>

namespace rockcut::dem {

void ForceBuffers::prepare(int threads, std::size_t n) {
  threads_ = threads;
  force_.resize(threads > 1 ? threads - 1 : 0);
  torque_.resize(force_.size());
  for (std::size_t t = 0; t < force_.size(); ++t) {
    force_[t].assign(2 * n, 0.0);
    torque_[t].assign(n, 0.0);
  }
}

ForceView ForceBuffers::view(int thread, Particles& p) {
  if (thread == 0) return {p.force.data(), p.torque.data()};
  return {force_[thread - 1].data(), torque_[thread - 1].data()};
}

void ForceBuffers::reduce(Particles& p) {
  const std::size_t n = p.size();
  for (std::size_t t = 0; t < force_.size(); ++t) {
    const double* f = force_[t].data();
    const double* q = torque_[t].data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      p.force[2 * i] += f[2 * i];
      p.force[2 * i + 1] += f[2 * i + 1];
      p.torque[i] += q[i];
    }
  }
}

}  // namespace rockcut::dem
