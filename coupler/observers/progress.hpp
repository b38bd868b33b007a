// The progress line: simulated time, steps, wall time and ETA. On a terminal one line is redrawn in
// place a few times a second; otherwise (logs, CI) a plain line is printed every few seconds.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>

#include "observers/run_observer.hpp"

namespace rockcut::coupler {

class Progress : public RunObserver {
 public:
  /// `start_step`: where a resumed run starts (the ETA extrapolates from the steps since).
  Progress(double end_time_s, std::uint64_t total_steps, std::FILE* stream,
           std::uint64_t start_step = 0);
  /// Cheap when nothing is due: compares the clock only.
  void update(double time_s, std::uint64_t step);
  /// Prints the final line (and a newline on a terminal).
  void print_final(double time_s, std::uint64_t step);
  void exchanged(const RunClock& clock) override { update(clock.time_s, clock.step); }
  bool finish(const RunClock& clock, Summary&, bool completed) override {
    if (completed) print_final(clock.time_s, clock.step);
    return true;
  }
  double elapsed_s() const;

 private:
  void print(double time_s, std::uint64_t step, bool final);

  double end_time_s_;
  std::uint64_t total_steps_;
  std::uint64_t start_step_;
  std::FILE* stream_;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point next_print_;
};

}  // namespace rockcut::coupler
