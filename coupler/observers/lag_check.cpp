#include "observers/lag_check.hpp"

#include <cstdio>
#include <vector>

namespace rockcut::coupler {

void LagCheck::row(const RunClock& clock) {
  const double* travel = clock.scalar("tool_travel_m");
  const double* correction = clock.scalar("lag_correction_j");
  const double* fluid = clock.scalar("external_work_j");
  const double* tool = clock.scalar("boundary_work_j");
  if (!travel || !correction || !fluid || !tool) return;
  // A window is closed at the first row at least kWindowM on (to round-off: rows fall on it).
  if (started_ && *travel - start_travel_m_ >= kWindowM * (1.0 - 1e-9)) {
    const double taken_j = *correction - start_correction_j_;
    const double dissipated_j = -(*fluid - start_fluid_work_j_);  // the fluid's work is a sink
    ++windows_;
    if (taken_j > dissipated_j && taken_j > kNegligibleShare * *tool) {
      if (resolved_ == 0) first_resolved_m_ = start_travel_m_;
      ++resolved_;
    }
    started_ = false;  // the next window starts at this row
  }
  if (!started_) {
    started_ = true;
    start_travel_m_ = *travel;
    start_correction_j_ = *correction;
    start_fluid_work_j_ = *fluid;
  }
}

bool LagCheck::finish(const RunClock&, Summary& summary, bool) {
  summary.set("lag_windows", static_cast<std::int64_t>(windows_));
  summary.set("lag_resolved_windows", static_cast<std::int64_t>(resolved_));
  if (windows_ == 0) return true;
  if (resolved_ == 0) {
    std::fprintf(stderr,
                 "lag        the correction took less than the pore fluid dissipated in %s%llu "
                 "window%s of %g mm of the tool's travel\n",
                 windows_ == 1 ? "its " : "all ", static_cast<unsigned long long>(windows_),
                 windows_ == 1 ? "" : "s", kWindowM * 1e3);
  } else {
    std::fprintf(stderr,
                 "lag        the correction took more than the pore fluid dissipated in %llu of "
                 "%llu windows of %g mm of the tool's travel (the first from %.1f mm): there the "
                 "lag, not Darcy flow, set the energy; a smaller coupling.interval shrinks the lag, "
                 "1 has none (docs/record/results.md, \"The lag's energy taken out at paper scale\")\n",
                 static_cast<unsigned long long>(resolved_),
                 static_cast<unsigned long long>(windows_), kWindowM * 1e3,
                 first_resolved_m_ * 1e3);
  }
  return true;
}

void LagCheck::save_state(state::StateArchive& a) const {
  a.put("lag_check", std::vector<double>{started_ ? 1.0 : 0.0, start_travel_m_, start_correction_j_,
                                         start_fluid_work_j_, static_cast<double>(windows_),
                                         static_cast<double>(resolved_), first_resolved_m_});
}

void LagCheck::load_state(const state::StateArchive& a) {
  if (!a.has("lag_check")) return;  // a checkpoint written without the check: start afresh
  const auto v = a.values("lag_check", 7);
  started_ = v[0] != 0.0;
  start_travel_m_ = v[1];
  start_correction_j_ = v[2];
  start_fluid_work_j_ = v[3];
  windows_ = static_cast<std::uint64_t>(v[4]);
  resolved_ = static_cast<std::uint64_t>(v[5]);
  first_resolved_m_ = v[6];
}

}  // namespace rockcut::coupler
