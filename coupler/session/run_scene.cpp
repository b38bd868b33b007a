// `coupler run` / `coupler resume`: read the scene (or the checkpoint to continue), take the output
// directory, and hand both to a RunSession.
#include <iostream>

#include "run/out_dir_lock.hpp"
#include "checkpoint/resume.hpp"
#include "session/run_session.hpp"
#include "run/signals.hpp"

namespace rockcut::coupler {

namespace fs = std::filesystem;

// A packing file named in the scene is relative to the scene file; the DEM gets it absolute.
void make_paths_absolute(scene::LoadedScene& loaded) {
  if (!loaded.scene.dem().has_packing_file()) return;
  const fs::path p(loaded.scene.dem().packing_file().path());
  if (p.is_relative()) {
    loaded.scene.mutable_dem()->mutable_packing_file()->set_path(
        fs::absolute(loaded.path.parent_path() / p).lexically_normal().string());
  }
}

int run_scene(const RunOptions& options_in) {
  RunOptions options = options_in;
  std::optional<Checkpoint> checkpoint;
  scene::LoadedScene loaded;
  std::optional<OutDirLock> lock;
  try {
    if (!options.resume) loaded = scene::load_scene(options.scene_path, options.overrides);
    if (options.out_dir.empty()) options.out_dir = fs::path("out") / loaded.path.stem();
    try {
      lock.emplace(options.out_dir);  // before anything in it is read or changed
    } catch (const std::runtime_error& e) {
      std::cerr << "error: " << e.what() << "\n";
      return kExitBadInput;
    }
    if (options.resume || options.resume_if_possible) {
      if (const int code = choose_checkpoint(options, loaded, checkpoint); code != kExitOk) {
        return code;
      }
    }
    // A fresh run would replace an earlier run's output at its first step: only when asked to.
    if (!checkpoint && !options.overwrite && fs::exists(options.out_dir / "run.h5")) {
      std::cerr << "error: " << options.out_dir.string()
                << " holds the output of an earlier run (run.h5): give --overwrite to replace it, "
                   "use coupler resume to continue it, or choose another --out\n";
      return kExitBadInput;
    }
  } catch (const scene::SceneError& e) {
    std::cerr << e.what() << (std::string(e.what()).ends_with('\n') ? "" : "\n");
    return kExitBadInput;
  }
  install_stop_signal_handlers();
  make_paths_absolute(loaded);
  RunSession session(options, std::move(loaded), std::move(checkpoint));
  return session.run();
}

}  // namespace rockcut::coupler
