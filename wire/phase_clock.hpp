#pragma once
// Where a module's step spends its wall time: laps between fixed points of the step, taken by one
// thread (the OpenMP team's first). A lap is one steady_clock read (tens of nanoseconds), taken a
// few times per step and never per particle. With several threads a phase's time includes the
// first thread's wait at the barrier that ends it; a separate "barrier" phase, where a module
// has one, holds the wait for the slowest thread. Header-only and free of messages, so that the
// modules' cores keep one without linking the wire.
#include <chrono>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace rockcut::wire {

// On cache lines of its own: the first thread writes it inside parallel regions, and the other
// threads must not find the fields they read beside it.
class alignas(64) PhaseClock {
 public:
  explicit PhaseClock(std::vector<std::string> names)
      : names_(std::move(names)), seconds_(names_.size(), 0.0) {}

  /// Starts a stretch of laps (the beginning of a step or of one of its parts).
  void start() { last_ = clock::now(); }
  /// Adds the time since the last start or lap to `phase` (an index into the names).
  void lap(std::size_t phase) {
    const clock::time_point now = clock::now();
    seconds_[phase] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }
  double seconds(std::size_t phase) const { return seconds_[phase]; }
  const std::vector<std::string>& names() const { return names_; }
  /// The cumulative times, in the order of the names, into a reply's Envelope.phase_times (a
  /// template so that a module's core, which knows no messages, can keep a clock).
  template <typename Envelope>
  void write(Envelope& envelope) const {
    envelope.clear_phase_times();
    for (std::size_t k = 0; k < names_.size(); ++k) {
      auto* p = envelope.add_phase_times();
      p->set_name(names_[k]);
      p->set_seconds(seconds_[k]);
    }
  }

 private:
  using clock = std::chrono::steady_clock;
  std::vector<std::string> names_;
  std::vector<double> seconds_;
  clock::time_point last_ = clock::now();
};

}  // namespace rockcut::wire
