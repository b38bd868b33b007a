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

void report_rebuilds(const RunClock& clock, Summary& summary) {
  // The counts since the run's start, from the last report each module sent (kept over resumes).
  const double* lists = clock.scalar("neighbour_rebuilds");
  const double* refreshes = clock.scalar("fluid_geometry_updates");
  const double* local = clock.scalar("fluid_geometry_local_updates");
  const double* rows = clock.scalar("fluid_geometry_rows_recomputed");
  if (lists) summary.set("dem_neighbour_rebuilds", static_cast<std::int64_t>(*lists));
  if (refreshes) summary.set("fluid_geometry_updates", static_cast<std::int64_t>(*refreshes));
  if (local) summary.set("fluid_geometry_local_updates", static_cast<std::int64_t>(*local));
  if (rows) summary.set("fluid_geometry_rows_recomputed", static_cast<std::int64_t>(*rows));
  if (!lists && !refreshes) return;
  std::string line = "rebuilds  ";
  char part[160];
  if (lists) {
    std::snprintf(part, sizeof part, " DEM neighbour lists %.0f", *lists);
    line += part;
  }
  if (refreshes) {
    std::snprintf(part, sizeof part, "%s fluid geometry %.0f (%.0f local), %.4g rows recomputed",
                  lists ? ";" : "", *refreshes, local ? *local : 0.0, rows ? *rows : 0.0);
    line += part;
  }
  const double steps = static_cast<double>(clock.step);
  if (steps > 0) {
    std::snprintf(part, sizeof part, ", over %.0f steps", steps);
    line += part;
  }
  std::printf("%s\n", line.c_str());
}

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
  report_rebuilds(run.clock, summary);
}

}  // namespace rockcut::coupler
