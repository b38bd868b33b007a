#include "core/force_buffers.hpp"

#include <algorithm>

namespace rockcut::dem {

void ForceBuffers::resize(int threads, std::size_t n) {
  threads_ = threads;
  force_.resize(threads > 1 ? threads - 1 : 0);
  torque_.resize(force_.size());
  for (std::size_t t = 0; t < force_.size(); ++t) {
    force_[t].resize(2 * n);
    torque_[t].resize(n);
  }
}

void ForceBuffers::zero(int thread) {
  std::fill(force_[thread - 1].begin(), force_[thread - 1].end(), 0.0);
  std::fill(torque_[thread - 1].begin(), torque_[thread - 1].end(), 0.0);
}

ForceView ForceBuffers::view(int thread, Particles& p) {
  if (thread == 0) return {p.force.data(), p.torque.data()};
  return {force_[thread - 1].data(), torque_[thread - 1].data()};
}

void ForceBuffers::reduce(Particles& p, std::size_t begin, std::size_t end) const {
  for (std::size_t t = 0; t < force_.size(); ++t) {
    const double* f = force_[t].data();
    const double* q = torque_[t].data();
    for (std::size_t i = begin; i < end; ++i) {
      p.force[2 * i] += f[2 * i];
      p.force[2 * i + 1] += f[2 * i + 1];
      p.torque[i] += q[i];
    }
  }
}

}  // namespace rockcut::dem
