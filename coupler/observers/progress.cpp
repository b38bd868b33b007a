#include "observers/progress.hpp"

#include <unistd.h>

#include <algorithm>

namespace rockcut::coupler {

namespace {
// A terminal line is redrawn at 4 Hz; log lines every 10 s keep CI logs short.
constexpr std::chrono::milliseconds kTtyPeriod{250};
constexpr std::chrono::milliseconds kLogPeriod{10000};
}  // namespace

Progress::Progress(double end_time_s, std::uint64_t total_steps, std::FILE* stream,
                   std::uint64_t start_step)
    : end_time_s_(end_time_s),
      total_steps_(total_steps),
      start_step_(start_step),
      stream_(stream),
      tty_(isatty(fileno(stream)) != 0),
      start_(std::chrono::steady_clock::now()),
      next_print_(start_ + (tty_ ? kTtyPeriod : kLogPeriod)) {}

double Progress::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(double time_s, std::uint64_t step) {
  const auto now = std::chrono::steady_clock::now();
  if (now < next_print_) return;
  next_print_ = now + (tty_ ? kTtyPeriod : kLogPeriod);
  print(time_s, step, false);
}

void Progress::print_final(double time_s, std::uint64_t step) { print(time_s, step, true); }

void Progress::print(double time_s, std::uint64_t step, bool final) {
  const double wall = elapsed_s();
  const double fraction =
      total_steps_ > start_step_
          ? static_cast<double>(step - std::min(step, start_step_)) / (total_steps_ - start_step_)
          : 1.0;
  const double eta = fraction > 0 ? wall * (1.0 - fraction) / fraction : 0.0;
  std::fprintf(stream_, "%st = %.4g / %.4g s  step %llu / %llu  wall %.1f s  ETA %.1f s%s",
               tty_ ? "\r" : "", time_s, end_time_s_, static_cast<unsigned long long>(step),
               static_cast<unsigned long long>(total_steps_), wall, eta,
               tty_ ? (final ? "\n" : "   ") : "\n");
  std::fflush(stream_);
}

}  // namespace rockcut::coupler
