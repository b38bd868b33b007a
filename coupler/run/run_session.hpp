// One `coupler run`: load the scene, start the modules it needs, hand-shake, plan the time step,
// drive the half-step synchronised loop (DESIGN section 3), record output, and end cleanly whatever
// happens (module failure, stall, signal).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <zmq.hpp>

#include "output/run_file.hpp"
#include "output/summary_json.hpp"
#include "run/calibration_summary.hpp"
#include "run/cutting_summary.hpp"
#include "run/peclet.hpp"
#include "run/pressure_nodes.hpp"
#include "run/module_link.hpp"
#include "run/progress.hpp"
#include "run/time_plan.hpp"
#include "scene/scene_loader.hpp"

namespace rockcut::coupler {

/// Process exit codes of `coupler run`.
enum ExitCode : int {
  kExitOk = 0,
  kExitVerificationFailed = 1,
  kExitBadInput = 2,
  kExitModuleFailed = 3,
  kExitUnstable = 4,  ///< a runtime guard stopped the run (NaN, runaway kinetic energy, overlap)
};

/// A module reported a tripped runtime guard (wire GuardTrip): the run stops as failed.
struct GuardStop {
  std::string module;  ///< label of the module that reported it
  wire::GuardTrip trip;
};

struct RunOptions {
  std::filesystem::path scene_path;
  std::vector<std::string> overrides;  ///< --set path=value
  std::filesystem::path out_dir;       ///< empty: out/<scene file stem>
  Transport transport = Transport::ipc;
  std::string dem_endpoint = "tcp://127.0.0.1:5555";    ///< tcp only
  std::string fluid_endpoint = "tcp://127.0.0.1:5556";  ///< tcp only
  std::filesystem::path module_dir;    ///< where dem_module and fluid_module are (the coupler's dir)
};

/// Runs the scene and returns the exit code. Messages go to stderr, the result lines to stdout.
int run_scene(const RunOptions& options);

class RunSession {
 public:
  RunSession(const RunOptions& options, scene::LoadedScene scene);
  ~RunSession();
  int run();

 private:
  struct ModuleInfo {
    std::unique_ptr<ModuleLink> link;
    wire::HelloReply hello;
    wire::InitReply init;
  };

  // run_session.cpp: set-up and tear-down
  void start_modules();
  void init_modules();
  void choose_pressure_nodes();
  void check_frame_fields();
  void open_output();
  void print_startup() const;
  int finish(int code, const std::string& status, const std::string& reason);
  /// Writes the last frame and the guard into the summary; returns the exit code.
  int stop_on_guard(const GuardStop& stop);
  std::filesystem::path module_executable(const std::string& from_scene, const char* name) const;

  // run_loop.cpp: the clock
  void loop();
  void exchange(unsigned steps, bool initial);
  /// Whether a time-series row or a frame is due at this step and time (or it is the last step):
  /// only then must an exchange complete its step before the next Advance.
  bool record_due(std::uint64_t step, double time_s) const;
  bool series_due(std::uint64_t step) const;
  bool frame_due(double time_s) const;
  void advance_dry(unsigned steps);
  /// How long the DEM may take to answer an Advance of `steps` steps.
  std::chrono::milliseconds allowance(std::uint64_t steps) const;
  void record_step_report(const wire::StepReport& report);
  void maybe_record(bool force_frame);
  void write_frame();
  void write_breaks(const wire::Message& frame);

  RunOptions options_;
  scene::LoadedScene loaded_;
  const rockcut::Scene& scene_;
  bool coupled_ = false;

  std::optional<zmq::context_t> context_;
  std::filesystem::path ipc_dir_;
  ModuleInfo dem_;
  std::optional<ModuleInfo> fluid_;
  TimePlan plan_;
  std::vector<std::string> dem_frame_fields_, fluid_frame_fields_;

  std::unique_ptr<RunFile> run_file_;
  std::unique_ptr<CuttingSummary> cutting_;
  std::vector<PressureNodeBox> nodes_;      // sent as probes when the fluid has a pressure
  std::optional<PecletNumber> peclet_;
  std::optional<std::string> accuracy_line_;  // expected error from docs/accuracy.md, if covered
  // Each module's handling time (Envelope.busy_s, after_reply_s) at the start of the loop and now.
  struct BusyTime {
    double busy0_s = 0.0, busy_s = 0.0, after0_s = 0.0, after_s = 0.0;
    void read(const wire::Envelope& e) {
      busy_s = e.busy_s();
      after_s = e.after_reply_s();
    }
    void start_loop() {
      busy0_s = busy_s;
      after0_s = after_s;
    }
  };
  BusyTime dem_busy_, fluid_busy_;
  std::unique_ptr<CalibrationSummary> calibration_;
  bool dem_logs_breaks_ = false;  // the DEM hands out its bond breaks with every frame
  Summary summary_;
  std::unique_ptr<Progress> progress_;

  // Clock state (advanced by the loop).
  double time_s_ = 0.0;
  std::uint64_t step_ = 0;
  std::uint64_t next_series_step_ = 0;
  std::uint64_t next_frame_index_ = 0;
  std::uint64_t exchanges_ = 0;
  bool forces_held_ = false;  // fluid_reply_ holds forces for the next Advance to apply first
  std::uint64_t bytes_exchanged_ = 0;
  std::uint64_t bytes_in_shared_memory_ = 0;  // the part of it the modules wrote to shared memory
  std::vector<std::pair<std::string, double>> scalars_;
  std::vector<double> initial_position_, last_position_;
  // Final per-particle fields the verification compares (e.g. the fluid's pressure).
  std::vector<std::string> verification_fields_;
  std::map<std::string, std::vector<double>> final_fields_;

  // Reused messages: no allocation of message objects per exchange.
  wire::Message request_, reply_, fluid_request_, fluid_reply_;
};

}  // namespace rockcut::coupler
