// What a run says about itself: run.h5's attributes, the start-up report on stderr, and at the
// end summary.json (the observers' results, the counters, where the wall time went) and the
// closing of run.h5.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "output/summary_json.hpp"
#include "session/run_parts.hpp"

namespace rockcut::coupler {

/// run.h5's attributes: versions, scene, transport, modules, status "running".
std::map<std::string, std::string> run_attributes(const RunParts& run);
/// The summary fields known at the start.
void start_summary(const RunParts& run, Summary& summary);
/// The start-up report: scene, modules, the time plan, the scheme, the observers' lines.
void print_startup(const RunParts& run, const std::vector<std::string>& observer_lines);
/// The end of a run (`wall_s`: the loop's wall time): the observers' results and the counters into
/// the summary, run.h5 closed with its status, summary.json written. Returns the exit code:
/// `code`, or kExitVerificationFailed / kExitOutputFailed where a check or the output failed.
int finish_run(const RunParts& run, Summary& summary, double wall_s, int code,
               const std::string& status, const std::string& reason);
/// A guard stopped the run: the state that tripped it as a last row and frame (for a look in
/// ParaView), the guard in the summary, then finish_run. Returns kExitUnstable.
int stop_on_guard(const RunParts& run, Summary& summary, double wall_s, const GuardStop& stop);

}  // namespace rockcut::coupler
