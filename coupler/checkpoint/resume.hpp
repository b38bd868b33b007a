// Choosing the checkpoint a run resumes from, and what may change when it does
// (resume.cpp). Writing checkpoints during a run: checkpoint/checkpoint_writer.hpp.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "checkpoint/checkpoint_file.hpp"
#include "output/run_file.hpp"
#include "run/run_options.hpp"
#include "scene/scene_loader.hpp"
#include "wire/state_archive.hpp"

namespace rockcut::coupler {

/// The scene fields a resumed run may change (end time, output cadence, checkpoint settings,
/// title, timeout), as dotted paths.
const std::vector<std::string>& resume_allowed_fields();
/// How `now` differs from `saved` outside resume_allowed_fields(), one line per field (empty:
/// the same physics); the allowed differences go into `allowed` as "path: old -> new".
std::vector<std::string> scene_differences(const rockcut::Scene& saved, const rockcut::Scene& now,
                                           std::vector<std::string>* allowed);
/// `coupler resume` / `coupler run --resume`: the newest checkpoint of options.out_dir that is
/// whole, of this version and of this scene, falling back past damaged ones, into `checkpoint`,
/// with the scene the run continues with into `loaded`. Returns kExitOk, or kExitBadInput after
/// saying why no checkpoint can be used (`checkpoint` stays empty and nothing in out_dir is
/// changed). With resume_if_possible and no checkpoint at all, kExitOk.
int choose_checkpoint(const RunOptions& options, scene::LoadedScene& loaded,
                      std::optional<Checkpoint>& checkpoint);
/// A packing file named in the scene is relative to the scene file: made absolute for the DEM.
void make_paths_absolute(scene::LoadedScene& loaded);
/// How far run.h5 had been written, as a checkpoint stores it.
void save_extent(state::StateArchive& a, const RunFileExtent& extent);
RunFileExtent load_extent(const state::StateArchive& a);

}  // namespace rockcut::coupler
