#include "session/time_split.hpp"

#include <cstdio>
#include <string>

namespace rockcut::coupler {
namespace {

// One module's part: its phases and service work into the summary; its busy time, its largest
// phases as shares of it, and the coupler's wait on it into `line`.
double add_module(const std::string& who, const RunModule& m, Summary& summary,
                  std::string& line) {
  const BusyTime& b = m.busy;
  const double busy_s = b.busy_s - b.busy0_s;
  const double request_s = m.link->request_s() - m.request0_s;
  double phases_s = 0.0;
  std::string parts;
  for (std::size_t k = 0; k < b.phases.size(); ++k) {
    const double s = b.phase_s(k);
    phases_s += s;
    summary.set(who + "_phase_" + b.phases[k].first + "_s", s);
    if (busy_s > 0 && s >= 0.05 * busy_s) {
      char part[96];
      std::snprintf(part, sizeof part, "%s%s %.0f %%", parts.empty() ? "" : ", ",
                    b.phases[k].first.c_str(), 100.0 * s / busy_s);
      parts += part;
    }
  }
  if (!b.phases.empty()) summary.set(who + "_service_s", busy_s - phases_s);
  summary.set(who + "_request_s", request_s);
  char text[160];
  std::snprintf(text, sizeof text, "%s busy %.3g s", who.c_str(), busy_s);
  line += text;
  if (!parts.empty()) line += " (" + parts + ")";
  return request_s;
}

}  // namespace

void report_time_split(const RunParts& run, Summary& summary, double loop_wall_s) {
  std::string line;
  double requests_s = add_module("dem", run.modules.dem(), summary, line);
  if (const RunModule* fluid = run.modules.fluid()) {
    line += "; ";
    requests_s += add_module("fluid", *fluid, summary, line);
  }
  // Everything the coupler did outside its requests: output, observers, the scheme.
  const double own_s = loop_wall_s - requests_s;
  summary.set("coupler_own_s", own_s);
  if (loop_wall_s > 0) {
    std::printf("time       %s; coupler's own work %.1f %% of %.3g s\n", line.c_str(),
                100.0 * own_s / loop_wall_s, loop_wall_s);
  }
}

}  // namespace rockcut::coupler
