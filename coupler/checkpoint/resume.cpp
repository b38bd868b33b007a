// Checkpoint and restart of a run (README "Checkpoint and restart"). The coupler asks each module
// for its state (SaveState), adds its own clock, accumulators and how far run.h5 has been written,
// and stores all of it in one checkpoint file (checkpoint/checkpoint_file.hpp). A resumed run starts
// the modules from the scene as usual, hands them their states back (LoadState), cuts run.h5 back
// to the checkpoint and continues: the same arithmetic in the same order, so the same bits.
#include <cmath>
#include <cstdio>
#include <iostream>

#include <google/protobuf/text_format.h>
#include <google/protobuf/util/message_differencer.h>

#include "output/run_file.hpp"
#include "run/text_lines.hpp"
#include "checkpoint/resume.hpp"
#include "run/signals.hpp"
#include "wire/protocol.hpp"
#include "wire/state_message.hpp"

namespace rockcut::coupler {

namespace {

namespace fs = std::filesystem;
using clock_type = std::chrono::steady_clock;



}  // namespace

// Fields a resumed run may change: they decide when the run ends, what it records, how it
// checkpoints and how it uses the cores, not the physics of a step.
const std::vector<std::string>& resume_allowed_fields() {
  static const std::vector<std::string> fields = {
      "title",
      "time.end_time_s",
      "output.frame_interval_s",
      "output.timeseries_every_steps",
      "output.checkpoint_interval_s",
      "output.checkpoints_kept",
      "coupling.timeout_s",
      // How the work is laid out on the cores: the fluid's and the overlap's bits are the same
      // at any setting; the DEM's sums its forces in another order at another thread count.
      "coupling.overlap",
      "fluid.threads",
      "dem.threads",
  };
  return fields;
}

namespace {

// The field at dotted `path` of `message`, cleared; returns its old value as text, or "" when unset.
// A message left empty by it is cleared too (`--set coupling.overlap=off` on a scene without a
// `coupling` block adds the block, which is no difference of its own), except `fluid`, whose
// presence makes a scene coupled: `--set fluid.threads=2` on a dry run stays a difference.
std::string take_field(google::protobuf::Message& message, const std::string& path) {
  std::vector<std::pair<google::protobuf::Message*, const google::protobuf::FieldDescriptor*>> chain;
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
      for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        const auto* r = it->first->GetReflection();
        if (it->second->name() == "fluid" ||
            r->GetMessage(*it->first, it->second).ByteSizeLong() != 0) {
          break;
        }
        r->ClearField(it->first, it->second);
      }
      return value;
    }
    chain.emplace_back(m, field);
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

void save_extent(state::StateArchive& a, const RunFileExtent& e) {
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

RunFileExtent load_extent(const state::StateArchive& a) {
  RunFileExtent e;
  const auto counts = a.values("output_extent", 2);
  e.timeseries_rows = static_cast<std::uint64_t>(counts[0]);
  e.frames = static_cast<std::uint64_t>(counts[1]);
  e.timeseries_columns = split_lines(a.text("timeseries_columns"));
  for (const std::string& table : split_lines(a.text("tables"))) {
    e.table_rows[table] = a.scalar_as<std::uint64_t>("table_rows:" + table);
    e.table_columns[table] = split_lines(a.text("table_columns:" + table));
  }
  return e;
}

namespace {

// The scene a run continues with: the checkpoint's own (`coupler resume`) or the named file's
// (`coupler run --resume`), with the --set overrides.
scene::LoadedScene resumed_scene(const RunOptions& options, const Checkpoint& c,
                                 const fs::path& file) {
  scene::LoadedScene loaded;
  if (options.resume) {
    loaded = scene::parse_scene(c.scene_text, file.string() + " (its scene)", options.overrides);
    loaded.path = c.scene_path;
    std::vector<std::string> all = c.overrides;
    all.insert(all.end(), options.overrides.begin(), options.overrides.end());
    loaded.overrides = all;
  } else {
    loaded = scene::load_scene(options.scene_path, options.overrides);
  }
  make_paths_absolute(loaded);
  return loaded;
}

// Why checkpoint `c` cannot continue a run of `now` (empty: it can); prints allowed changes.
std::string refuse_reason(const Checkpoint& c, const scene::LoadedScene& now) {
  if (c.rockcut_version != ROCKCUT_VERSION || c.protocol_version != wire::kProtocolVersion) {
    return "written by rockcut " + c.rockcut_version + " (protocol " +
           std::to_string(c.protocol_version) + "); this is rockcut " ROCKCUT_VERSION +
           std::string(" (protocol ") + std::to_string(wire::kProtocolVersion) +
           "): a run resumes only with the program that wrote its checkpoint";
  }
  scene::LoadedScene saved;
  try {
    saved = scene::parse_scene(c.scene_text, "checkpoint scene");
  } catch (const scene::SceneError& e) {
    return std::string("its scene no longer validates: ") + e.what();
  }
  std::vector<std::string> allowed;
  const std::vector<std::string> differ = scene_differences(saved.scene, now.scene, &allowed);
  if (!differ.empty()) {
    std::string reason = "the scene differs in what can change the physics:";
    for (const std::string& d : differ) reason += "\n  " + d;
    return reason + "\n(a resumed run may change only: " + [] {
      std::string list;
      for (const std::string& f : resume_allowed_fields()) list += (list.empty() ? "" : ", ") + f;
      return list;
    }() + ")";
  }
  for (const std::string& a : allowed) std::fprintf(stderr, "resume     changed %s\n", a.c_str());
  return "";
}

// The scene OUT/run.h5 was written with (`coupler resume` takes its scene from a checkpoint, so
// this is what a checkpoint must match to belong to the run); none without a readable run.h5.
// A scene that no longer parses is an error string for every checkpoint.
struct RunScene {
  std::optional<rockcut::Scene> scene;
  std::string error;
};
RunScene run_scene_of(const fs::path& out_dir) {
  RunScene r;
  const std::optional<std::string> text = stored_scene_text(out_dir);
  if (!text) return r;
  try {
    r.scene = scene::parse_scene(*text, (out_dir / "run.h5").string() + " (its scene)").scene;
  } catch (const scene::SceneError& e) {
    r.error = std::string("the run's own scene in run.h5 no longer validates: ") + e.what();
  }
  return r;
}

// Why a checkpoint whose scene is `candidate` is not the run's (a checkpoint of another run copied
// into checkpoints/): its scene differs from the run's beyond what a resume may change. Empty: it
// is the run's.
std::string foreign_reason(const RunScene& run, const scene::LoadedScene& candidate,
                           const fs::path& out_dir) {
  if (!run.error.empty()) return run.error;
  if (!run.scene) return "";
  const std::vector<std::string> differ = scene_differences(*run.scene, candidate.scene, nullptr);
  if (differ.empty()) return "";
  std::string reason = "it belongs to another run: its scene differs from " +
                       (out_dir / "run.h5").string() + "'s in:";
  for (const std::string& d : differ) reason += "\n  " + d;
  return reason;
}

}  // namespace

int choose_checkpoint(const RunOptions& options, scene::LoadedScene& loaded,
                      std::optional<Checkpoint>& checkpoint) {
  const fs::path dir = options.out_dir / "checkpoints";
  const std::vector<fs::path> files = list_checkpoints(dir);
  if (files.empty() && options.resume) {
    std::cerr << options.out_dir.string() << ": no checkpoint to resume from (" << dir.string()
              << " holds none)\n";
    return kExitBadInput;
  }
  // `coupler resume` takes the scene from the checkpoint: the run's own scene, in run.h5, is what
  // a checkpoint must match to belong to it.
  const RunScene run_scene = options.resume ? run_scene_of(options.out_dir) : RunScene{};
  bool damaged_only = true;  // a refused scene or version holds for the older ones too
  for (std::size_t k = 0; k < files.size() && !checkpoint && damaged_only; ++k) {
    std::string reason;
    try {
      const auto read_start = clock_type::now();
      Checkpoint c = read_checkpoint(files[k]);
      const double read_s = std::chrono::duration<double>(clock_type::now() - read_start).count();
      scene::LoadedScene candidate = resumed_scene(options, c, files[k]);
      reason = refuse_reason(c, candidate);
      damaged_only = reason.empty();
      // A foreign checkpoint says nothing of the older ones, which may be the run's own.
      if (reason.empty()) reason = foreign_reason(run_scene, candidate, options.out_dir);
      if (reason.empty()) {
        checkpoint = std::move(c);
        loaded = std::move(candidate);
        std::fprintf(stderr, "resume     from %s (step %llu, t = %.6g s; read in %.3g s)\n",
                     files[k].c_str(), static_cast<unsigned long long>(checkpoint->step),
                     checkpoint->time_s, read_s);
      }
    } catch (const CheckpointError& e) {
      reason = e.what();
    }
    if (!reason.empty()) {
      std::fprintf(stderr, "%s: refused: %s\n", files[k].c_str(), reason.c_str());
      if (k + 1 < files.size() && damaged_only) {
        std::fprintf(stderr, "resume     falling back to %s\n", files[k + 1].c_str());
      }
    }
  }
  if (!checkpoint && !files.empty()) {
    std::cerr << options.out_dir.string() << ": no usable checkpoint; nothing in it was changed\n";
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace rockcut::coupler
