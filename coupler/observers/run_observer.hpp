// What a run computes besides advancing and recording: summaries, checks and reports, each an
// observer the run calls at fixed points. The scene decides which exist (observers/
// run_observers.cpp): a dry scene builds no pressure nodes, a cut no calibration fit.
// Every call is per exchange or per record, never per particle.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "output/run_file.hpp"
#include "output/summary_json.hpp"
#include "rockcut/wire.pb.h"
#include "run/run_clock.hpp"
#include "wire/state_archive.hpp"

namespace rockcut::coupler {

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  /// Before the loop: summary fields known at the start, lines for the start-up report.
  virtual void start(Summary& /*summary*/, std::vector<std::string>& /*report*/) {}
  /// A coupled exchange whose step is recorded is about to send its FluidStep, with the
  /// kinematics the DEM answered: add what this observer asks of the fluid (probes).
  virtual void prepare_fluid_step(const wire::Kinematics& /*kinematics*/,
                                  wire::FluidStep& /*step*/) {}
  /// A time-series row was written: `clock.scalars` holds it.
  virtual void row(const RunClock& /*clock*/) {}
  /// A frame was written with these fields (positions among them).
  virtual void frame(const RunClock& /*clock*/, std::span<const FrameField> /*fields*/) {}
  /// After every exchange; must be cheap.
  virtual void exchanged(const RunClock& /*clock*/) {}
  /// True when the run should end now (a Brazilian disc has split).
  virtual bool ends_run() const { return false; }
  /// Why it ended the run, one line for the terminal (ends_run() true); the run loop knows no scene.
  virtual std::string end_reason(const RunClock& /*clock*/) const { return {}; }
  /// The end of the run (`completed`: it reached its end time): summary fields and report lines.
  /// Returns false when a check of the run failed (the run exits with kExitVerificationFailed).
  virtual bool finish(const RunClock& /*clock*/, Summary& /*summary*/, bool /*completed*/) {
    return true;
  }
  /// Checkpoints: what this observer has accumulated.
  virtual void save_state(state::StateArchive& /*a*/) const {}
  virtual void load_state(const state::StateArchive& /*a*/) {}
};

/// An observer that takes every time-series row as a sample and writes its summary fields at the
/// end (the cutting, calibration and fracture summaries). Called per row, never per particle.
class RowSummary : public RunObserver {
 public:
  /// One time-series sample of the DEM's scalars (sorted by name).
  virtual void observe(const std::vector<std::pair<std::string, double>>& scalars) = 0;
  virtual void write(Summary& summary) const = 0;
  void row(const RunClock& clock) override { observe(clock.scalars); }
  bool finish(const RunClock& /*clock*/, Summary& summary, bool /*completed*/) override {
    write(summary);
    return true;
  }
};

/// The observers of one run, called in the order they were registered.
class RunObservers {
 public:
  void add(std::unique_ptr<RunObserver> observer) { list_.push_back(std::move(observer)); }
  /// Called before all others (the progress line ends before other lines are printed).
  void add_first(std::unique_ptr<RunObserver> observer) {
    list_.insert(list_.begin(), std::move(observer));
  }
  template <class F>
  void each(F&& f) const {
    for (const auto& o : list_) f(*o);
  }
  bool ends_run() const {
    for (const auto& o : list_) {
      if (o->ends_run()) return true;
    }
    return false;
  }
  /// The reason of the first observer that ends the run (empty if none does).
  std::string end_reason(const RunClock& clock) const {
    for (const auto& o : list_) {
      if (o->ends_run()) return o->end_reason(clock);
    }
    return {};
  }
  std::size_t size() const { return list_.size(); }
  /// The first observer of type T, or nullptr.
  template <class T>
  T* find() const {
    for (const auto& o : list_) {
      if (auto* p = dynamic_cast<T*>(o.get())) return p;
    }
    return nullptr;
  }

 private:
  std::vector<std::unique_ptr<RunObserver>> list_;
};

}  // namespace rockcut::coupler
