#include "run/run_clock.hpp"

#include <algorithm>

#include "run/reply_checks.hpp"

namespace rockcut::coupler {

void RunClock::take_step_report(const wire::StepReport& report, const std::string& module) {
  check_scalar_names(module, report.scalars());
  time_s = report.time_s();
  step = report.step();
  // protobuf maps have no stable order: sorted, every run writes the same columns.
  for (const auto& [name, value] : report.scalars()) scalars.emplace_back(name, value);
  std::sort(scalars.begin(), scalars.end());
  if (report.has_guard()) throw GuardStop{module, report.guard()};
}

const double* find_value(const NamedValues& values, const std::string& name) {
  for (const auto& [key, value] : values) {
    if (key == name) return &value;
  }
  return nullptr;
}

}  // namespace rockcut::coupler
