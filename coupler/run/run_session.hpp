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

#include "output/checkpoint_file.hpp"
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
  kExitOutputFailed = 5,  ///< the output could not be written (a full disk, a file-size limit)
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
  /// tcp only: key directory (wire/curve_keys.hpp) for CURVE sessions; empty: plain tcp.
  std::filesystem::path curve_keys;
  std::filesystem::path module_dir;    ///< where dem_module and fluid_module are (the coupler's dir)
  /// Wall time between two checkpoints [s]; 0: none on wall time.
  double checkpoint_every_s = 600.0;
  /// No checkpoint at all (nor at SIGUSR1, SIGTERM or the end): signals stop at once.
  bool no_checkpoints = false;
  /// `coupler resume OUT`: continue the run in out_dir from its newest valid checkpoint, with the
  /// scene the checkpoint holds (scene_path unused; `overrides` may change what cannot change
  /// the physics).
  bool resume = false;
  /// `coupler run CASE --resume`: as `resume` when out_dir holds a checkpoint, else a fresh run.
  bool resume_if_possible = false;
  /// A fresh run may replace the output of an earlier run in out_dir (else it is refused).
  bool overwrite = false;
};

/// Runs the scene and returns the exit code. Messages go to stderr, the result lines to stdout.
int run_scene(const RunOptions& options);

/// The scene fields a resumed run may change (end time, output cadence, checkpoint settings,
/// title, timeout), as dotted paths.
const std::vector<std::string>& resume_allowed_fields();
/// How `now` differs from `saved` outside resume_allowed_fields(), one line per field (empty:
/// the same physics); the allowed differences go into `allowed` as "path: old -> new".
std::vector<std::string> scene_differences(const rockcut::Scene& saved, const rockcut::Scene& now,
                                           std::vector<std::string>* allowed);
/// `coupler resume` / `coupler run --resume` (run_checkpoint.cpp): the newest checkpoint of
/// options.out_dir that is whole, of this version and of this scene, falling back past damaged
/// ones, into `checkpoint`, with the scene the run continues with into `loaded`. Returns
/// kExitOk, or kExitBadInput after saying why no checkpoint can be used (`checkpoint` stays empty
/// and nothing in out_dir is changed). With resume_if_possible and no checkpoint at all, kExitOk.
int choose_checkpoint(const RunOptions& options, scene::LoadedScene& loaded,
                      std::optional<Checkpoint>& checkpoint);
/// A packing file named in the scene is relative to the scene file: made absolute for the DEM.
void make_paths_absolute(scene::LoadedScene& loaded);
/// How far run.h5 had been written, as a checkpoint stores it (run_checkpoint.cpp).
void save_extent(state::StateArchive& a, const RunFileExtent& extent);
RunFileExtent load_extent(const state::StateArchive& a);

class RunSession {
 public:
  /// `resume_from`: the checkpoint a resumed run continues from (already read and verified).
  RunSession(const RunOptions& options, scene::LoadedScene scene,
             std::optional<Checkpoint> resume_from = std::nullopt);
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

  // run_checkpoint.cpp: checkpoint and restart
  /// Writes a checkpoint now (between two exchanges, no forces held).
  void write_checkpoint_now(const char* why);
  /// After an exchange: writes a checkpoint if one is due (simulated or wall time, SIGUSR1, a
  /// stop), or asks the next exchange to complete its step first; throws Interrupted after the
  /// checkpoint of a stop.
  void maybe_checkpoint();
  void save_state(state::StateArchive& a) const;
  void load_state(const state::StateArchive& a);
  /// Refuses a checkpoint whose scene differs from this one in what can change the physics;
  /// reports the allowed differences.
  void check_resume_scene() const;
  /// Hands the saved states back to the modules and to the coupler.
  void restore_from_checkpoint();

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

  // Checkpoints.
  std::optional<Checkpoint> resume_from_;
  bool checkpoints_ = true;          // off with --no-checkpoints or a module that cannot save
  bool checkpoint_due_ = false;      // the next exchange completes its step for a checkpoint
  bool checkpoint_requested_ = false;  // SIGUSR1 seen, checkpoint not yet written
  double next_checkpoint_time_s_ = 0.0;  // simulated time of the next one (interval > 0)
  double wall_at_last_checkpoint_s_ = 0.0;
  double wall_before_s_ = 0.0;  // wall time of the earlier parts of a resumed run

  // Clock state (advanced by the loop).
  double time_s_ = 0.0;
  std::uint64_t step_ = 0;
  std::uint64_t next_series_step_ = 0;
  std::uint64_t next_frame_index_ = 0;
  // The steps of the last row and frame written: the end of a run adds one only where none is.
  std::uint64_t row_step_ = static_cast<std::uint64_t>(-1);
  std::uint64_t frame_step_ = static_cast<std::uint64_t>(-1);
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
