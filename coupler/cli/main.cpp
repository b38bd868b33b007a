// coupler: the command line of rockcut.
//   coupler run CASE [--out DIR] [--transport ipc|inproc|tcp] [--set path=value ...]
//   coupler resume OUT [--set path=value ...]    continue a run from its newest valid checkpoint
//   coupler validate CASE [--set path=value ...] [--print]
//   coupler keygen DIR                           CURVE keys for tcp sessions (README, "Security")
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "output/h5_handle.hpp"
#include "session/run_session.hpp"
#include "scene/scene_loader.hpp"
#include "wire/curve_keys.hpp"
#include "wire/module_main.hpp"

namespace {

namespace fs = std::filesystem;
using rockcut::coupler::Transport;

fs::path own_directory() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::current_path() : exe.parent_path();
}

int validate(const fs::path& scene_path, const std::vector<std::string>& overrides, bool print) {
  try {
    const auto loaded = rockcut::scene::load_scene(scene_path, overrides);
    const rockcut::Scene& s = loaded.scene;
    std::cout << scene_path.string() << ": ok (" << (s.has_fluid() ? "coupled, fluid model " +
                                                                         s.fluid().model()
                                                                   : std::string("dry"))
              << ", end time " << s.time().end_time_s() << " s)\n";
    if (print) std::cout << loaded.effective_text();
    return 0;
  } catch (const rockcut::scene::SceneError& e) {
    std::cerr << e.what() << (std::string(e.what()).ends_with('\n') ? "" : "\n");
    return rockcut::coupler::kExitBadInput;
  }
}

}  // namespace

int main(int argc, char** argv) {
  rockcut::coupler::h5::keep_library_out_of_exit();
  rockcut::wire::tune_allocator_for_bulk_frames();
  CLI::App app{"rockcut coupler: runs discrete-element rock cutting coupled to a pore-pressure "
               "model (Helmons, Miedema & van Rhee). Exit codes: 0 ok, 1 verification failed, "
               "2 bad scene or refused settings, 3 a module failed, 4 a runtime guard stopped the run "
               "(NaN, runaway kinetic energy, excessive overlap), 5 the output could not be written, 128+N "
               "stopped by signal N."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("coupler ") + ROCKCUT_VERSION);

  rockcut::coupler::RunOptions options;
  options.module_dir = own_directory();
  std::string scene_path;
  std::vector<std::string> overrides;

  CLI::App* run = app.add_subcommand("run", "Run a scene and write OUT/summary.json, run.h5, run.xdmf");
  run->add_option("CASE", scene_path, "Scene file (protobuf text format)")->required();
  run->add_option("--out", options.out_dir, "Output directory (default: out/<scene name>)");
  const std::map<std::string, Transport> transports = {
      {"ipc", Transport::ipc}, {"inproc", Transport::inproc}, {"tcp", Transport::tcp}};
  run->add_option("--transport", options.transport,
                  "ipc: modules as local processes (default); inproc: modules as threads of the "
                  "coupler; tcp: attach to modules started by hand with --bind")
      ->transform(CLI::CheckedTransformer(transports, CLI::ignore_case));
  run->add_option("--set", overrides, "Override a scalar scene field: dotted.path=value (repeatable)")
      ->allow_extra_args(false);
  run->add_option("--dem-endpoint", options.dem_endpoint, "tcp: where dem_module serves")
      ->capture_default_str();
  run->add_option("--fluid-endpoint", options.fluid_endpoint, "tcp: where fluid_module serves")
      ->capture_default_str();
  run->add_option("--curve-keys", options.curve_keys,
                  "tcp: key directory (`coupler keygen`) with coupler.secret, coupler.public and "
                  "the modules' public keys: the sessions are authenticated and encrypted (CURVE); "
                  "start the modules with the same --curve-keys");

  run->add_option("--checkpoint-every", options.checkpoint_every_s,
                  "Wall time between two checkpoints in OUT/checkpoints/ [s]; 0: none on wall time "
                  "(SIGUSR1, SIGTERM, SIGINT and the end of the run still write one)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  run->add_flag("--no-checkpoints", options.no_checkpoints,
                "Write no checkpoint at all; SIGINT and SIGTERM then stop at once");
  run->add_flag("--overwrite", options.overwrite,
                "Replace the output of an earlier run in OUT (without it such a directory is "
                "refused, and the earlier run stays whole)");
  run->add_flag("--resume", options.resume_if_possible,
                "If OUT holds a checkpoint, continue from it (the scene may change only the end "
                "time, output cadence and checkpoint settings); else start afresh. The same "
                "command then serves a first start and every restart (a requeued batch job)");

  rockcut::coupler::RunOptions resume_options;
  resume_options.module_dir = options.module_dir;
  std::string resume_dir;
  CLI::App* resume = app.add_subcommand(
      "resume", "Continue the run in OUT from its newest valid checkpoint, with the scene the "
                "checkpoint holds; appends to OUT/run.h5 as if the run had never stopped");
  resume->add_option("OUT", resume_dir, "Output directory of the run to continue")->required();
  resume->add_option("--set", resume_options.overrides,
                     "Change a field that cannot change the physics, e.g. time.end_time_s=0.2 "
                     "(repeatable)")
      ->allow_extra_args(false);
  resume->add_option("--transport", resume_options.transport, "As for run")
      ->transform(CLI::CheckedTransformer(transports, CLI::ignore_case));
  resume->add_option("--dem-endpoint", resume_options.dem_endpoint, "As for run");
  resume->add_option("--fluid-endpoint", resume_options.fluid_endpoint, "As for run");
  resume->add_option("--curve-keys", resume_options.curve_keys, "As for run");
  resume->add_option("--checkpoint-every", resume_options.checkpoint_every_s, "As for run")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  resume->add_flag("--no-checkpoints", resume_options.no_checkpoints, "As for run");

  CLI::App* val = app.add_subcommand("validate", "Check a scene against the schema; start nothing");
  val->add_option("CASE", scene_path, "Scene file (protobuf text format)")->required();
  val->add_option("--set", overrides, "Override a scalar scene field: dotted.path=value")
      ->allow_extra_args(false);
  bool print = false;
  val->add_flag("--print", print,
                "Also print the effective scene (its bases merged, the overrides applied), as run.h5 "
                "stores it");

  std::string keys_dir;
  CLI::App* keygen = app.add_subcommand(
      "keygen", "Make CURVE key pairs (coupler, dem_module, fluid_module; NAME.public and "
                "NAME.secret, the secret files readable by you only) in DIR for tcp sessions; "
                "copy DIR/coupler.public and a module's own pair to the host that runs it");
  keygen->add_option("DIR", keys_dir, "Key directory (made with mode 0700)")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (keygen->parsed()) {
    try {
      rockcut::wire::make_curve_keys(keys_dir, {"coupler", "dem_module", "fluid_module"});
      std::cout << "keys written to " << keys_dir << "\n";
      return 0;
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return rockcut::coupler::kExitBadInput;
    }
  }
  for (const rockcut::coupler::RunOptions* o : {&options, &resume_options}) {
    if (!o->curve_keys.empty() && o->transport != Transport::tcp) {
      std::cerr << "error: --curve-keys applies to --transport tcp only\n";
      return rockcut::coupler::kExitBadInput;
    }
  }
  if (val->parsed()) return validate(scene_path, overrides, print);
  if (resume->parsed()) {
    resume_options.out_dir = resume_dir;
    resume_options.resume = true;
    return rockcut::coupler::run_scene(resume_options);
  }
  options.scene_path = scene_path;
  options.overrides = overrides;
  return rockcut::coupler::run_scene(options);
}
