// Checkpoint and restart of a run (README "Checkpoint and restart"). The coupler asks each module
// for its state (SaveState), adds its own clock, accumulators and how far run.h5 has been written,
// and stores all of it in one checkpoint file (output/checkpoint_file.hpp). A resumed run starts
// the modules from the scene as usual, hands them their states back (LoadState), cuts run.h5 back
// to the checkpoint and continues: the same arithmetic in the same order, so the same bits.
#include <cmath>
#include <cstdio>
#include <iostream>

#include <google/protobuf/text_format.h>
#include <google/protobuf/util/message_differencer.h>

#include "output/text_lines.hpp"
#include "run/named_values_state.hpp"
#include "run/run_session.hpp"
#include "run/signals.hpp"
#include "wire/protocol.hpp"
#include "wire/state_message.hpp"

namespace rockcut::coupler {

namespace {

namespace fs = std::filesystem;
using clock_type = std::chrono::steady_clock;



}  // namespace

// Fields a resumed run may change: they decide when the run ends, what it records and how it
// checkpoints, not the physics of a step.
const std::vector<std::string>& resume_allowed_fields() {
  static const std::vector<std::string> fields = {
      "title",
      "time.end_time_s",
      "output.frame_interval_s",
      "output.timeseries_every_steps",
      "output.checkpoint_interval_s",
      "output.checkpoints_kept",
      "coupling.timeout_s",
  };
  return fields;
}

namespace {

// The field at dotted `path` of `message`, cleared; returns its old value as text, or "" when unset.
std::string take_field(google::protobuf::Message& message, const std::string& path) {
  google::protobuf::Message* m = &message;
  std::size_t start = 0;
  for (;;) {
    const std::size_t dot = path.find('.', start);
    const std::string name = path.substr(start, dot - start);
    const auto* field = m->GetDescriptor()->FindFieldByName(name);
    const auto* reflection = m->GetReflection();
    if (!field || !reflection->HasField(*m, field)) return "";
    if (dot == std::string::npos) {
      std::string value;
      google::protobuf::TextFormat::PrintFieldValueToString(*m, field, -1, &value);
      reflection->ClearField(m, field);
      return value;
    }
    m = reflection->MutableMessage(m, field);
    start = dot + 1;
  }
}

}  // namespace

std::vector<std::string> scene_differences(const rockcut::Scene& saved, const rockcut::Scene& now,
                                           std::vector<std::string>* allowed) {
  rockcut::Scene a = saved, b = now;
  for (const std::string& field : resume_allowed_fields()) {
    const std::string was = take_field(a, field), is = take_field(b, field);
    if (was != is && allowed) {
      allowed->push_back(field + ": " + (was.empty() ? "(default)" : was) + " -> " +
                         (is.empty() ? "(default)" : is));
    }
  }
  std::string report;
  google::protobuf::util::MessageDifferencer differencer;
  differencer.ReportDifferencesToString(&report);
  differencer.Compare(a, b);
  std::vector<std::string> out;
  for (std::string& line : split_lines(report)) {
    if (!line.empty()) out.push_back(std::move(line));
  }
  return out;
}

void RunSession::save_state(state::StateArchive& a) const {
  a.put("clock", std::vector<double>{time_s_, static_cast<double>(step_),
                                     static_cast<double>(next_series_step_),
                                     static_cast<double>(next_frame_index_),
                                     static_cast<double>(exchanges_),
                                     static_cast<double>(bytes_exchanged_),
                                     static_cast<double>(bytes_in_shared_memory_),
                                     next_checkpoint_time_s_});
  a.put("plan", std::vector<double>{plan_.dt_s, static_cast<double>(plan_.coupling_interval)});
  a.put_scalar("wall_time_s", wall_before_s_ + (progress_ ? progress_->elapsed_s() : 0.0));
  save_named_values(a, "scalars", scalars_);
  a.put("initial_position_m", initial_position_, 2);
  a.put("last_position_m", last_position_, 2);
  std::vector<std::string> names;
  for (const auto& [name, values] : final_fields_) {
    names.push_back(name);
    a.put("final_field:" + name, values);
  }
  a.put_text("final_fields", join_lines(names));
  cutting_->save_state(a);
  calibration_->save_state(a);
  const RunFileExtent e = run_file_->extent();
  a.put("output_extent", std::vector<double>{static_cast<double>(e.timeseries_rows),
                                             static_cast<double>(e.frames)});
  a.put_text("timeseries_columns", join_lines(e.timeseries_columns));
  std::vector<std::string> tables;
  for (const auto& [table, rows] : e.table_rows) {
    tables.push_back(table);
    a.put_scalar("table_rows:" + table, static_cast<double>(rows));
    a.put_text("table_columns:" + table, join_lines(e.table_columns.at(table)));
  }
  a.put_text("tables", join_lines(tables));
}

void RunSession::load_state(const state::StateArchive& a) {
  const auto clock = a.values("clock", 8);
  time_s_ = clock[0];
  step_ = static_cast<std::uint64_t>(clock[1]);
  next_series_step_ = static_cast<std::uint64_t>(clock[2]);
  next_frame_index_ = static_cast<std::uint64_t>(clock[3]);
  exchanges_ = static_cast<std::uint64_t>(clock[4]);
  bytes_exchanged_ = static_cast<std::uint64_t>(clock[5]);
  bytes_in_shared_memory_ = static_cast<std::uint64_t>(clock[6]);
  next_checkpoint_time_s_ = clock[7];
  wall_before_s_ = a.scalar("wall_time_s");
  scalars_ = load_named_values(a, "scalars");
  a.get("initial_position_m", initial_position_);
  a.get("last_position_m", last_position_);
  final_fields_.clear();
  for (const std::string& name : split_lines(a.text("final_fields"))) {
    a.get("final_field:" + name, final_fields_[name]);
  }
  cutting_->load_state(a);
  calibration_->load_state(a);
}

void RunSession::check_resume_scene() const {
  const Checkpoint& c = *resume_from_;
  const auto plan = c.parts.at("coupler").values("plan", 2);
  if (plan[0] != plan_.dt_s || plan[1] != static_cast<double>(plan_.coupling_interval)) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "the checkpoint's run stepped dt = %.17g s with N = %.0f, this one would step "
                  "dt = %.17g s with N = %u",
                  plan[0], plan[1], plan_.dt_s, plan_.coupling_interval);
    throw PlanError(line);
  }
}

void RunSession::restore_from_checkpoint() {
  const auto start = clock_type::now();
  Checkpoint& c = *resume_from_;
  auto hand_back = [](ModuleInfo& module, wire::Message& request, wire::Message& reply,
                      const state::StateArchive& part, const char* what) {
    request.clear();
    wire::State* body = request.envelope.mutable_load_state()->mutable_state();
    wire::put_state(part, *body, request);
    module.link->set_timeout(std::chrono::milliseconds(600000));
    module.link->request(request, reply);
    if (!reply.envelope.has_ack()) {
      throw wire::ModuleFailure(module.link->label(), std::string("answered LoadState (") + what +
                                                          ") without Ack");
    }
  };
  if (!c.parts.count("dem") || (fluid_ && !c.parts.count("fluid"))) {
    throw PlanError("the checkpoint holds no state for a module of this scene");
  }
  hand_back(dem_, request_, reply_, c.parts.at("dem"), "dem");
  if (fluid_) hand_back(*fluid_, fluid_request_, fluid_reply_, c.parts.at("fluid"), "fluid");
  load_state(c.parts.at("coupler"));
  std::size_t bytes = 0;
  for (const auto& [name, part] : c.parts) bytes += part.payload_bytes();
  std::fprintf(stderr, "resume     %.3g MB of state handed back to the modules in %.3g s\n",
               bytes / 1e6, std::chrono::duration<double>(clock_type::now() - start).count());
}

void RunSession::write_checkpoint_now(const char* why) {
  const auto start = clock_type::now();
  Checkpoint c;
  c.rockcut_version = ROCKCUT_VERSION;
  c.protocol_version = wire::kProtocolVersion;
  c.scene_text = loaded_.effective_text();
  c.scene_path = loaded_.path.string();
  c.overrides = loaded_.overrides;
  c.step = step_;
  c.time_s = time_s_;
  auto take = [](ModuleInfo& module, wire::Message& request, wire::Message& reply) {
    request.clear();
    request.envelope.mutable_save_state();
    module.link->set_timeout(std::chrono::milliseconds(600000));
    module.link->request(request, reply);
    if (!reply.envelope.has_state()) {
      throw wire::ModuleFailure(module.link->label(), "answered SaveState without State");
    }
    return wire::take_state(reply.envelope.state(), reply);
  };
  try {
    c.parts["dem"] = take(dem_, request_, reply_);
    if (fluid_) c.parts["fluid"] = take(*fluid_, fluid_request_, fluid_reply_);
  } catch (const wire::ModuleFailure& e) {
    if (!e.refused()) throw;
    // A module that cannot save its state (a third party's, say): the run goes on without.
    std::fprintf(stderr, "\ncheckpoint  none written: %s; checkpoints are off for this run\n",
                 e.what());
    checkpoints_ = false;
    set_graceful_stop(false);
    return;
  }
  save_state(c.parts["coupler"]);
  std::size_t bytes = 0;
  for (const auto& [name, part] : c.parts) bytes += part.payload_bytes();
  const fs::path dir = options_.out_dir / "checkpoints";
  try {
    run_file_->flush();  // run.h5 on disk holds at least what the checkpoint says it holds
    const fs::path file = write_checkpoint(dir, c);
    prune_checkpoints(dir, scene_.output().checkpoints_kept());
    const double seconds = std::chrono::duration<double>(clock_type::now() - start).count();
    std::fprintf(stderr, "\ncheckpoint  %s at t = %.6g s (step %llu): %s, %.3g MB in %.3g s\n", why,
                 time_s_, static_cast<unsigned long long>(step_), file.c_str(), bytes / 1e6,
                 seconds);
  } catch (const std::exception& e) {
    // The run itself is fine: say so and go on (the previous checkpoint stays).
    std::fprintf(stderr, "\ncheckpoint  not written (%s): %s\n", why, e.what());
  }
}

void RunSession::maybe_checkpoint() {
  if (!checkpoints_) return;
  if (take_checkpoint_request()) checkpoint_requested_ = true;
  const bool last = step_ >= plan_.total_steps || calibration_->test_over();
  const bool stopping = stop_signal() != 0 && !last;
  const double interval = scene_.output().checkpoint_interval_s();
  const bool sim_due = interval > 0 && time_s_ >= next_checkpoint_time_s_ - 0.5 * plan_.dt_s;
  const double wall = progress_->elapsed_s();
  const bool wall_due = options_.checkpoint_every_s > 0 &&
                        wall - wall_at_last_checkpoint_s_ >= options_.checkpoint_every_s;
  if (!(checkpoint_due_ || checkpoint_requested_ || stopping || sim_due || wall_due)) return;
  if (last && !stopping) return;  // the end of the run writes one anyway
  if (forces_held_) {
    checkpoint_due_ = true;  // the next exchange completes its step (DESIGN section 3)
    return;
  }
  const char* why = stopping ? "stop" : checkpoint_requested_ ? "SIGUSR1"
                                      : sim_due                ? "interval"
                                                               : "wall time";
  checkpoint_due_ = false;
  checkpoint_requested_ = false;
  if (sim_due) next_checkpoint_time_s_ = (std::floor(time_s_ / interval + 0.5) + 1.0) * interval;
  wall_at_last_checkpoint_s_ = wall;
  write_checkpoint_now(why);
  if (stopping) throw wire::Interrupted();
}

}  // namespace rockcut::coupler
