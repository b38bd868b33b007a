// The command line: validate every case, refuse bad scenes before anything starts.
#include <gtest/gtest.h>

#include <fstream>

#include "integration/process_helpers.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;

TEST(Cli, EveryCaseValidates) {
  const fs::path dir = fresh_dir("validate_cases");
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(source("cases"))) {
    if (entry.path().extension() != ".pbtxt") continue;
    // cases/rock/ holds rock descriptions that scenes start from (`base:`), not scenes.
    if (entry.path().parent_path().filename() == "rock") continue;
    ++count;
    std::string out, err;
    EXPECT_EQ(run({bin("coupler"), "validate", entry.path().string()}, dir, "validate", &out, &err),
              0)
        << entry.path() << "\n" << err;
    EXPECT_NE(out.find(": ok"), std::string::npos) << out;
  }
  EXPECT_GE(count, 2);
}

TEST(Cli, BadSceneIsRefusedWithLocationAndStartsNothing) {
  const fs::path dir = fresh_dir("bad_scene");
  const fs::path scene = dir / "bad.pbtxt";
  std::ofstream(scene) << "time {\n  end_time_s: 0.01\n  dt_s: -1\n}\n"
                          "dem { lattice { nx: 2 ny: 2 spacing_m: 0.001 radius_m: 0.0004 } }\n";
  for (const std::string verb : {"validate", "run"}) {
    std::string out, err;
    std::vector<std::string> argv = {bin("coupler"), verb, scene.string()};
    if (verb == "run") argv.insert(argv.end(), {"--out", (dir / "out").string()});
    EXPECT_EQ(run(argv, dir, verb, &out, &err), 2) << err;
    EXPECT_NE(err.find(scene.string() + ":3:"), std::string::npos) << err;
    EXPECT_NE(err.find("dt_s"), std::string::npos) << err;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(Cli, SetOverridesAreCheckedLikeTheFile) {
  const fs::path dir = fresh_dir("bad_set");
  std::string out, err;
  EXPECT_EQ(run({bin("coupler"), "validate", source("cases/verification/free_fall.pbtxt"), "--set",
                 "time.end_tme_s=1"},
                dir, "validate", &out, &err),
            2);
  EXPECT_NE(err.find("--set:1:"), std::string::npos) << err;
  EXPECT_NE(err.find("end_time_s"), std::string::npos) << err;  // the suggestion
}

TEST(Cli, RefusedTimeStepNamesTheLimit) {
  // No contacts and no dt: no limit bounds the step, so the run is refused with what to set.
  const fs::path dir = fresh_dir("no_dt");
  const fs::path scene = dir / "no_dt.pbtxt";
  std::ofstream(scene) << "time { end_time_s: 0.01 }\n"
                          "dem { lattice { nx: 2 ny: 2 spacing_m: 0.001 radius_m: 0.0004 } }\n";
  std::string out, err;
  EXPECT_EQ(run({bin("coupler"), "run", scene.string(), "--out", (dir / "out").string()}, dir,
                "run", &out, &err),
            2);
  EXPECT_NE(err.find("set time.dt_s"), std::string::npos) << err;
}

TEST(Cli, HelpDescribesTheCommands) {
  const fs::path dir = fresh_dir("help");
  std::string out, err;
  EXPECT_EQ(run({bin("coupler"), "--help"}, dir, "help", &out, &err), 0);
  EXPECT_NE(out.find("run"), std::string::npos);
  EXPECT_NE(out.find("validate"), std::string::npos);
}

}  // namespace
}  // namespace rockcut::test
