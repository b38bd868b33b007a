#include "session/run_report.hpp"

#include <cstdio>
#include <iostream>

#include "observers/peclet.hpp"
#include "session/time_split.hpp"
#include "wire/protocol.hpp"

namespace rockcut::coupler {

std::map<std::string, std::string> run_attributes(const RunParts& run) {
  const RunModule& dem = run.modules.dem();
  std::map<std::string, std::string> attributes = {
      {"rockcut_version", ROCKCUT_VERSION},
      {"protocol_version", std::to_string(wire::kProtocolVersion)},
      {"scene_path", run.loaded.path.string()},
      {"transport", transport_name(run.options.transport)},
      {"dem_module", dem.hello.module_name() + " " + dem.hello.module_version()},
      {"status", "running"}};
  if (const RunModule* fluid = run.modules.fluid()) {
    attributes["fluid_module"] = fluid->hello.module_name() + " " + fluid->hello.module_version();
    attributes["fluid_model"] = fluid->init.model();
  }
  return attributes;
}

void start_summary(const RunParts& run, Summary& summary) {
  const rockcut::Scene& scene = run.loaded.scene;
  const RunModule* fluid = run.modules.fluid();
  summary.set("scene", run.loaded.path.string());
  summary.set("title", scene.title());
  summary.set("transport", std::string(transport_name(run.options.transport)));
  summary.set("particles", static_cast<std::int64_t>(run.modules.particle_count()));
  summary.set("dt_s", run.plan.dt_s);
  summary.set("coupling_interval", static_cast<std::int64_t>(run.plan.coupling_interval));
  summary.set("coupling_scheme", std::string(run.scheme.name()));
  summary.set("fluid_model", fluid ? fluid->init.model() : std::string("none"));
  if (fluid) {
    summary.set("water_depth_m", scene.water_depth_m());
    summary.set("hydrostatic_pressure_pa", hydrostatic_pressure_pa(scene));
  }
}

void print_startup(const RunParts& run, const std::vector<std::string>& observer_lines) {
  const rockcut::Scene& scene = run.loaded.scene;
  const RunModule& dem = run.modules.dem();
  std::fprintf(stderr, "scene      %s%s\n", run.loaded.path.c_str(),
               scene.title().empty() ? "" : (" (" + scene.title() + ")").c_str());
  std::fprintf(stderr, "transport  %s\n", transport_name(run.options.transport));
  std::fprintf(stderr, "dem        %s %s, %llu particles\n", dem.label().c_str(),
               dem.hello.module_version().c_str(),
               static_cast<unsigned long long>(run.modules.particle_count()));
  if (const RunModule* fluid = run.modules.fluid()) {
    std::fprintf(stderr, "fluid      %s %s, model %s, needs [%s]\n", fluid->label().c_str(),
                 fluid->hello.module_version().c_str(), fluid->init.model().c_str(),
                 join_names(fluid->init.needs()).c_str());
    std::fprintf(stderr, "water      depth %.6g m, p_hydro %.6g Pa\n", scene.water_depth_m(),
                 hydrostatic_pressure_pa(scene));
  } else {
    std::fprintf(stderr, "fluid      none (dry scene: no fluid process)\n");
  }
  for (const std::string& note : dem.init.notes()) std::fprintf(stderr, "dem        %s\n", note.c_str());
  for (const std::string& line : run.plan.report) std::fprintf(stderr, "%s\n", line.c_str());
  std::fprintf(stderr, "coupling   %s\n", run.scheme.name());
  for (const std::string& line : observer_lines) std::fprintf(stderr, "%s\n", line.c_str());
  std::fprintf(stderr, "output     %s\n", run.options.out_dir.c_str());
}

int stop_on_guard(const RunParts& run, Summary& summary, double wall_s, const GuardStop& stop) {
  const wire::GuardTrip& g = stop.trip;
  std::fprintf(stderr,
               "\nerror: %s stopped the run (guard %s): %s\n"
               "       at t = %.6g s (step %llu), particle %lld at (%.6g, %.6g) m; output so far, "
               "with the last frame, in %s\n",
               stop.module.c_str(), g.guard().c_str(), g.message().c_str(), g.time_s(),
               static_cast<unsigned long long>(run.clock.step), static_cast<long long>(g.particle()),
               g.x_m(), g.y_m(), run.options.out_dir.c_str());
  // The state that tripped the guard, for a look in ParaView; the modules still answer frames.
  try {
    run.recorder.write_row(run.clock);
    run.recorder.write_frame(run.clock);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "       (the last frame could not be written: %s)\n", e.what());
  }
  summary.set("failure_guard", g.guard());
  summary.set("failure_module", stop.module);
  summary.set("failure_time_s", g.time_s());
  summary.set("failure_particle", static_cast<std::int64_t>(g.particle()));
  summary.set("failure_x_m", g.x_m());
  summary.set("failure_y_m", g.y_m());
  summary.set("failure_value", g.value());
  summary.set("failure_limit", g.limit());
  return finish_run(run, summary, wall_s, kExitUnstable, "failed",
                    g.guard() + " guard: " + g.message());
}

int finish_run(const RunParts& run, Summary& summary, double wall_s, int code,
               const std::string& status, const std::string& reason) {
  const RunClock& clock = run.clock;
  const double wall = clock.wall_before_s + wall_s;
  const std::uint64_t particles = run.modules.particle_count();
  const double rate = wall > 0 ? static_cast<double>(particles) * clock.step / wall : 0.0;
  bool checks_passed = true;
  run.observers.each([&](RunObserver& o) {
    checks_passed = o.finish(clock, summary, status == "completed") && checks_passed;
  });
  if (!checks_passed && code == kExitOk) code = kExitVerificationFailed;
  summary.set("status", status);
  if (!reason.empty()) summary.set("error", reason);
  summary.set("time_s", clock.time_s);
  summary.set("steps", static_cast<std::int64_t>(clock.step));
  summary.set("exchanges", static_cast<std::int64_t>(clock.exchanges));
  summary.set("bytes_exchanged", static_cast<std::int64_t>(clock.bytes_exchanged));
  summary.set("bytes_in_shared_memory", static_cast<std::int64_t>(clock.bytes_in_shared_memory));
  summary.set("wall_time_s", wall);
  summary.set("particle_steps_per_s", rate);
  // Where the wall time went: each module's own handling time during the loop, and the part of it
  // after its replies, which overlaps the other module's work (the DEM's contact forces during
  // the fluid step). The rest of the wall is the transport, the coupler's output and waiting.
  auto busy = [&](const std::string& who, const RunModule& m) {
    summary.set(who + "_busy_s", m.busy.busy_s - m.busy.busy0_s);
    summary.set(who + "_after_reply_s", m.busy.after_s - m.busy.after0_s);
  };
  busy("dem", run.modules.dem());
  if (const RunModule* fluid = run.modules.fluid()) busy("fluid", *fluid);
  report_time_split(run, summary, wall_s);
  // run.h5 and summary.json each on their own: a run.h5 that cannot be closed (a full disk)
  // still gets its summary.json, which then says so.
  const std::filesystem::path out = run.options.out_dir;
  try {
    if (run.recorder.is_open()) {
      RunFile& file = run.recorder.file();
      file.set_attribute("status", reason.empty() ? status : status + ": " + reason);
      file.set_attribute("wall_time_s", std::to_string(wall));
      file.close();
    }
  } catch (const std::exception& e) {
    std::cerr << "error: closing " << (out / "run.h5").string() << ": " << e.what() << "\n";
    if (code == kExitOk) code = kExitOutputFailed;
    summary.set("status", std::string("failed"));
    if (reason.empty()) summary.set("error", std::string("closing run.h5: ") + e.what());
  }
  try {
    summary.write(out / "summary.json");
  } catch (const std::exception& e) {
    std::cerr << "error: writing " << (out / "summary.json").string() << ": " << e.what() << "\n";
    if (code == kExitOk) code = kExitOutputFailed;
  }
  if (status == "completed") {
    std::printf("done: %llu steps of %llu particles in %.3f s wall (%.3g particle-steps/s); "
                "output in %s\n",
                static_cast<unsigned long long>(clock.step),
                static_cast<unsigned long long>(particles), wall, rate, out.c_str());
  }
  return code;
}

}  // namespace rockcut::coupler
