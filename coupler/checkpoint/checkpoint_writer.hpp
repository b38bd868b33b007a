// The checkpoints a run writes (README "Checkpoint and restart"): every
// output.checkpoint_interval_s of simulated time, every --checkpoint-every seconds of wall time, on
// SIGUSR1, on a stop (SIGTERM, SIGINT) and at the end; and the hand-back of one to a resumed run.
// Each module saves its own state (SaveState); the coupler adds its clock, what it has recorded and
// its observers' sums, into one file (checkpoint/checkpoint_file.hpp).
#pragma once

#include "checkpoint/checkpoint_file.hpp"
#include "session/run_parts.hpp"

namespace rockcut::coupler {

class RunCheckpoints {
 public:
  explicit RunCheckpoints(const RunParts& run);
  /// Off with --no-checkpoints, or once a module could not save its state.
  bool enabled() const { return enabled_; }
  /// The next exchange must complete its step: a checkpoint is waiting for it.
  bool due() const { return due_; }
  /// After an exchange (`wall_s`: the wall time of the loop so far): writes a checkpoint if one
  /// is due, or asks the next exchange to complete its step first; throws wire::Interrupted after
  /// the checkpoint of a stop.
  void after_exchange(double wall_s);
  /// Writes a checkpoint now (between two steps).
  void write_now(const char* why, double wall_s);
  /// Refuses a checkpoint of another time plan (PlanError); hands its states back to the modules
  /// and to the coupler.
  void restore(const Checkpoint& c);

 private:
  void save(state::StateArchive& a, double wall_s) const;
  void load(const state::StateArchive& a);

  RunParts run_;
  bool enabled_ = true;
  bool due_ = false;        // the next exchange completes its step for a checkpoint
  bool requested_ = false;  // SIGUSR1 seen, checkpoint not yet written
  double next_time_s_ = 0.0;  // simulated time of the next one (interval > 0)
  double wall_at_last_s_ = 0.0;
};

}  // namespace rockcut::coupler
