#include "core/force_buffers.hpp"

#include <algorithm>

namespace rockcut::dem {

void ForceBuffers::resize(int threads, std::size_t n) {
  const std::size_t buffers = threads > 1 ? static_cast<std::size_t>(threads) : 0;
  force_.resize(buffers);
  torque_.resize(buffers);
  window_begin_.resize(buffers, 0);
  window_end_.resize(buffers, 0);
  for (std::size_t t = 0; t < buffers; ++t) {
    if (force_[t].size() != 2 * n) force_[t].assign(2 * n, 0.0);  // new buffers start at zero
    if (torque_[t].size() != n) torque_[t].assign(n, 0.0);
  }
}

ForceView ForceBuffers::view(int thread, Particles& p, std::size_t own_begin, std::size_t own_end) {
  ForceView v{p.force.data(), p.torque.data(), p.force.data(), p.torque.data(), own_begin,
              own_end - own_begin};
  if (!force_.empty()) {
    v.other_force = force_[thread].data();
    v.other_torque = torque_[thread].data();
  }
  return v;
}

void ForceBuffers::set_window(int thread, std::size_t begin, std::size_t end) {
  window_begin_[thread] = begin;
  window_end_[thread] = std::max(begin, end);
}

void ForceBuffers::reduce(Particles& p, int thread, std::size_t begin, std::size_t end) {
  // In thread order: the same bits for the same thread count.
  for (std::size_t t = 0; t < force_.size(); ++t) {
    if (static_cast<int>(t) == thread) continue;
    const std::size_t b = std::max(begin, window_begin_[t]), e = std::min(end, window_end_[t]);
    double* f = force_[t].data();
    double* q = torque_[t].data();
    for (std::size_t i = b; i < e; ++i) {
      p.force[2 * i] += f[2 * i];
      p.force[2 * i + 1] += f[2 * i + 1];
      p.torque[i] += q[i];
      // Zeroed here, by the thread that owns these particles, ready for the next evaluation.
      f[2 * i] = f[2 * i + 1] = 0.0;
      q[i] = 0.0;
    }
  }
}

}  // namespace rockcut::dem
