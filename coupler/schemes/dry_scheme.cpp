#include "schemes/dry_scheme.hpp"

#include <algorithm>

#include "run/reply_checks.hpp"
#include "wire/protocol.hpp"

namespace rockcut::coupler {

std::uint64_t DryScheme::regular_steps(const RunClock& clock,
                                       const ExchangeSchedule& schedule) const {
  // Up to the next row or frame, with no message per step; at most 2^30 steps per message.
  return std::clamp<std::uint64_t>(schedule.steps_to_next_record(clock.step, clock.time_s), 1,
                                   1u << 30);
}

void DryScheme::advance_steps(RunClock& clock, unsigned steps) {
  RunModule& dem = modules_.dem();
  dem.request.clear();
  wire::Advance* advance = dem.request.envelope.mutable_advance();
  advance->set_steps(steps);
  advance->set_dt_s(plan_.dt_s);
  advance->set_split_last(false);
  dem.link->set_timeout(modules_.allowance(steps));
  dem.link->request(dem.request, dem.reply);
  if (!dem.reply.envelope.has_step_report()) {
    throw wire::ModuleFailure(dem.label(), "answered Advance without StepReport");
  }
  const wire::StepReport& r = dem.reply.envelope.step_report();
  check_progress(dem.label(), r.step(), r.time_s(), clock.step, clock.time_s, steps, r.has_guard());
  dem.busy.read(dem.reply.envelope);
  ++clock.exchanges;
  clock.scalars.clear();
  clock.take_step_report(r, dem.label());
}

}  // namespace rockcut::coupler
