// A scene that starts from another (`base:`): how the files merge, and that every problem is still
// reported at the file, line and column that wrote it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <google/protobuf/text_format.h>

#include <iterator>

#include "scene/scene_loader.hpp"

namespace {

namespace fs = std::filesystem;
using rockcut::scene::load_scene;
using rockcut::scene::SceneError;
using testing::HasSubstr;
using testing::Not;
using testing::StartsWith;

// A folder of scene files for the running test; write(name, text) returns the file's path.
class Files {
 public:
  Files() : dir_(fs::path(ROCKCUT_TEST_TMP) / "scene_base" /
                 testing::UnitTest::GetInstance()->current_test_info()->name()) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path.lexically_normal().string();
  }

 private:
  fs::path dir_;
};

constexpr const char* kBase =
    "title: \"base\"\n"
    "time { end_time_s: 0.5 dt_safety: 0.1 }\n"
    "dem {\n"
    "  lattice { nx: 2 ny: 3 spacing_m: 0.001 radius_m: 0.0004 }\n"
    "  damping { local_coefficient: 0.7 }\n"
    "}\n"
    "output { frame_fields: [\"position\", \"radius\"] }\n";

std::vector<std::string> errors_of(const std::string& path, const std::vector<std::string>& sets = {}) {
  try {
    load_scene(path, sets);
  } catch (const SceneError& e) {
    std::vector<std::string> lines;
    for (const auto& d : e.diagnostics()) lines.push_back(d.to_string());
    return lines;
  }
  ADD_FAILURE() << path << " loaded without error";
  return {};
}

TEST(SceneBase, MessagesMergeScalarsAndListsReplace) {
  const Files files;
  files.write("base.pbtxt", kBase);
  const auto scene = load_scene(files.write("derived.pbtxt",
                                            "base: \"base.pbtxt\"\n"
                                            "time { end_time_s: 0.25 }\n"
                                            "dem { lattice { ny: 5 } }\n"
                                            "output { frame_fields: [\"damage\"] }\n"))
                         .scene;
  EXPECT_EQ(scene.title(), "base");                      // not written: the base's
  EXPECT_EQ(scene.time().end_time_s(), 0.25);            // written: replaced
  EXPECT_EQ(scene.time().dt_safety(), 0.1);              // the rest of the block: merged
  EXPECT_EQ(scene.dem().lattice().nx(), 2);
  EXPECT_EQ(scene.dem().lattice().ny(), 5);
  EXPECT_EQ(scene.dem().damping().local_coefficient(), 0.7);
  ASSERT_EQ(scene.output().frame_fields_size(), 1);      // a list written: replaced, not appended
  EXPECT_EQ(scene.output().frame_fields(0), "damage");
  EXPECT_FALSE(scene.has_base());
}

TEST(SceneBase, EffectiveTextIsTheMergedSceneWithoutBase) {
  const Files files;
  files.write("base.pbtxt", kBase);
  const auto derived = load_scene(files.write("derived.pbtxt", "base: \"base.pbtxt\"\ntitle: \"derived\"\n"));
  std::string alone_text = kBase;
  alone_text.replace(alone_text.find("\"base\""), 6, "\"derived\"");
  const auto alone = load_scene(files.write("alone.pbtxt", alone_text));
  EXPECT_EQ(derived.effective_text(), alone.effective_text());
  EXPECT_THAT(derived.effective_text(), Not(HasSubstr("base")));
}

TEST(SceneBase, BasesChainAndPathsAreRelativeToTheFileThatNamesThem) {
  const Files files;
  files.write("rock/rock.pbtxt", "dem { damping { local_coefficient: 0.3 } density_kg_m3: 2500 }\n");
  files.write("cutting/scene.pbtxt", "base: \"../rock/rock.pbtxt\"\n" + std::string(kBase));
  const auto scene = load_scene(files.write("extreme/x.pbtxt",
                                            "base: \"../cutting/scene.pbtxt\"\n"
                                            "dem { density_kg_m3: 3000 }\n"))
                         .scene;
  EXPECT_EQ(scene.dem().damping().local_coefficient(), 0.7);  // the middle file overrides the rock
  EXPECT_EQ(scene.dem().density_kg_m3(), 3000);     // the last file overrides both
  EXPECT_EQ(scene.dem().lattice().ny(), 3);
}

TEST(SceneBase, OverridesApplyToTheMergedScene) {
  const Files files;
  files.write("base.pbtxt", kBase);
  const auto scene =
      load_scene(files.write("derived.pbtxt", "base: \"base.pbtxt\"\n"), {"dem.lattice.nx=7"}).scene;
  EXPECT_EQ(scene.dem().lattice().nx(), 7);
  EXPECT_EQ(scene.dem().lattice().ny(), 3);
}

TEST(SceneBase, ACycleIsRefusedWhereTheBaseIsNamed) {
  const Files files;
  const std::string a = files.write("a.pbtxt", "title: \"a\"\nbase: \"b.pbtxt\"\n");
  const std::string b = files.write("b.pbtxt", "base: \"a.pbtxt\"\n");
  const auto errors = errors_of(a);
  ASSERT_EQ(errors.size(), 1u) << testing::PrintToString(errors);
  EXPECT_THAT(errors[0], StartsWith(b + ":1:1: base \"a.pbtxt\": the bases form a cycle (a.pbtxt -> "
                                        "b.pbtxt -> a.pbtxt)"));
  const auto self = errors_of(files.write("self.pbtxt", std::string(kBase) + "base: \"self.pbtxt\"\n"));
  ASSERT_EQ(self.size(), 1u);
  EXPECT_THAT(self[0], HasSubstr("self.pbtxt:8:1: base \"self.pbtxt\": the bases form a cycle"));
}

TEST(SceneBase, AMissingBaseIsNamedWhereItIsWritten) {
  const Files files;
  const std::string scene = files.write("scene.pbtxt", "title: \"t\"\n  base: \"nowhere.pbtxt\"\n");
  const auto errors = errors_of(scene);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_THAT(errors[0], StartsWith(scene + ":2:3: base \"nowhere.pbtxt\": cannot read "));
  EXPECT_THAT(errors[0], HasSubstr("nowhere.pbtxt: No such file"));
}

TEST(SceneBase, SpecialAndHugeFilesAreRefusedUnread) {
  // A device read whole never ends (/dev/zero filled memory until std::bad_alloc), a FIFO blocks:
  // neither a scene nor a base may be anything but a regular file of at most 4 MiB.
  const Files files;
  for (const char* special : {"/dev/zero", "/dev/null"}) {
    const std::string scene =
        files.write("special.pbtxt", std::string("base: \"") + special + "\"\n");
    const auto errors = errors_of(scene);
    ASSERT_EQ(errors.size(), 1u) << special;
    EXPECT_THAT(errors[0], HasSubstr("not a regular file")) << special;
    try {
      load_scene(special);
      ADD_FAILURE() << special << " loaded as a scene";
    } catch (const SceneError& e) {
      EXPECT_THAT(e.diagnostics()[0].to_string(), HasSubstr("not a regular file")) << special;
    }
  }
  const std::string big = files.write("big.pbtxt", std::string((4u << 20) + 1, '#'));
  const auto errors = errors_of(files.write("scene.pbtxt", "base: \"big.pbtxt\"\n"));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_THAT(errors[0], HasSubstr("more than a scene's limit of 4194304"));
}

TEST(SceneBase, AnErrorInTheBaseIsReportedAtTheBasesLine) {
  const Files files;
  // Out of range (validation) and misspelt (parser) values in the base, one out of range in the
  // scene: each at its own file and line, the scene's first.
  const std::string base = files.write("base.pbtxt",
                                       "time { end_time_s: 0.5 }\n"
                                       "dem {\n"
                                       "  lattice { nx: 2 ny: 3 spacing_m: 0.001 radius_m: 0.0004 }\n"
                                       "  damping { local_coefficient: 1.5 }\n"
                                       "  densty_kg_m3: 2800\n"
                                       "}\n");
  const std::string scene = files.write("scene.pbtxt", "base: \"base.pbtxt\"\n\ntime { dt_safety: 2 }\n");
  const auto errors = errors_of(scene);
  ASSERT_EQ(errors.size(), 3u) << testing::PrintToString(errors);
  EXPECT_THAT(errors[0], StartsWith(scene + ":3:8: time.dt_safety = 2 is out of range"));
  EXPECT_THAT(errors[1], StartsWith(base + ":4:13: dem.damping.local_coefficient = 1.5 is out of range"));
  EXPECT_THAT(errors[2], StartsWith(base + ":5:3: Message type \"rockcut.Dem\" has no field named "
                                           "\"densty_kg_m3\" (did you mean \"density_kg_m3\"?)"));

  // A syntax error in the base stops the parse there, as in one file, and is named in the base.
  files.write("base.pbtxt", "time { end_time_s 0.5 }\n");
  const auto syntax = errors_of(scene);
  ASSERT_EQ(syntax.size(), 1u) << testing::PrintToString(syntax);
  EXPECT_THAT(syntax[0], StartsWith(base + ":1:19: Expected \":\""));
}

TEST(SceneBase, AValueTheSceneOverridesIsReportedInTheScene) {
  const Files files;
  files.write("base.pbtxt", kBase);
  const std::string scene = files.write("scene.pbtxt", "base: \"base.pbtxt\"\ndem {\n  damping { local_coefficient: -1 }\n}\n");
  const auto errors = errors_of(scene);
  ASSERT_EQ(errors.size(), 1u) << testing::PrintToString(errors);
  EXPECT_THAT(errors[0], StartsWith(scene + ":3:13: dem.damping.local_coefficient = -1 is out of range"));
}

TEST(SceneBase, MissingRequiredFieldsAreReportedAtTheScene) {
  const Files files;
  files.write("rock.pbtxt", "dem { damping { local_coefficient: 0.7 } }\n");
  const std::string scene = files.write("scene.pbtxt", "base: \"rock.pbtxt\"\n");
  const auto errors = errors_of(scene);
  ASSERT_FALSE(errors.empty());
  EXPECT_THAT(errors[0], StartsWith(scene + ":1:1: missing required field \"time\""));
}

TEST(SceneBase, BaseCannotBeSetFromTheCommandLine) {
  const Files files;
  files.write("base.pbtxt", kBase);
  const auto errors = errors_of(files.write("scene.pbtxt", kBase), {"base=base.pbtxt"});
  ASSERT_EQ(errors.size(), 1u) << testing::PrintToString(errors);
  EXPECT_THAT(errors[0], StartsWith("--set:1:1: \"base\" cannot be overridden"));
}

TEST(SceneBase, EveryExtremeSceneIsItsBaseAndAFewLines) {
  // The extreme scenes name what makes them extreme, nothing else: a change of the base reaches
  // them all. (A scene file of more than a dozen lines of fields has copied its base.)
  const fs::path extreme = fs::path(ROCKCUT_SOURCE_DIR) / "cases" / "extreme";
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(extreme)) {
    // initial_overlaps.pbtxt is a lattice in a box, no cut: it is the base of its refused variant.
    if (entry.path().extension() != ".pbtxt" || entry.path().filename() == "initial_overlaps.pbtxt")
      continue;
    ++scenes;
    std::ifstream in(entry.path());
    int fields = 0;
    bool has_base = false;
    for (std::string line; std::getline(in, line);) {
      const auto start = line.find_first_not_of(' ');
      if (start == std::string::npos || line[start] == '#' || line[start] == '}') continue;
      ++fields;
      has_base = has_base || line.compare(start, 5, "base:") == 0;
    }
    EXPECT_TRUE(has_base) << entry.path();
    EXPECT_LE(fields, 12) << entry.path();
  }
  EXPECT_GE(scenes, 10);
}

TEST(SceneBase, TheRockOfTheCuttingAndCalibrationScenesIsWrittenOnce) {
  // The rock (bonds, contact, density) is written only in cases/rock/; every cutting and
  // calibration scene gets it from there, so that changing the rock edits one file (the coarse
  // discs' strengths, scaled with their size, in default_rock_coarse.pbtxt). A scene cut under
  // dashpots has the strengths calibrated under them (default_rock_viscous{,_coarse}.pbtxt): its
  // one base is the local-damping cut it varies, so it writes them, and must write that file's;
  // a scene with softening bonds, default_rock_softening{,_coarse}.pbtxt's strengths and lambda.
  const fs::path cases = fs::path(ROCKCUT_SOURCE_DIR) / "cases";
  rockcut::Scene rock, coarse, viscous, viscous_coarse, softening, softening_coarse;
  for (auto [file, scene] :
       {std::pair{"default_rock.pbtxt", &rock}, {"default_rock_coarse.pbtxt", &coarse},
        {"default_rock_viscous.pbtxt", &viscous},
        {"default_rock_viscous_coarse.pbtxt", &viscous_coarse},
        {"default_rock_softening.pbtxt", &softening},
        {"default_rock_softening_coarse.pbtxt", &softening_coarse}}) {
    std::ifstream in(cases / "rock" / file);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(text, scene)) << file;
  }
  int scenes = 0;
  for (const char* folder : {"cutting", "calibration"}) {
    for (const auto& entry : fs::directory_iterator(cases / folder)) {
      if (entry.path().extension() != ".pbtxt") continue;
      ++scenes;
      std::ifstream in(entry.path());
      const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      const rockcut::Dem dem = load_scene(entry.path()).scene.dem();
      const bool dashpots = dem.damping().model() == "viscous";
      for (const char* field : {"bonds", "contact", "density_kg_m3"}) {
        if (dashpots && std::string(field) == "bonds") continue;
        EXPECT_EQ(text.find(std::string("\n  ") + field), std::string::npos)
            << entry.path() << " writes the rock's " << field << ": take it from cases/rock/";
      }
      const bool is_coarse = dem.specimen().radius_max_m() == coarse.dem().specimen().radius_max_m();
      const bool softens = dem.bonds().softening_ratio() > 0;
      // The files compose (base:): the softening rock's lambda is in the fine file only.
      const rockcut::Dem& want =
          softens    ? (is_coarse ? softening_coarse.dem() : softening.dem())
          : dashpots ? (is_coarse ? viscous_coarse.dem() : viscous.dem())
          : is_coarse ? coarse.dem()
                      : rock.dem();
      EXPECT_EQ(dem.bonds().softening_ratio(), softens ? softening.dem().bonds().softening_ratio() : 0.0)
          << entry.path();
      EXPECT_EQ(dem.bonds().shear_strength_n_per_m(), want.bonds().shear_strength_n_per_m())
          << entry.path();
      EXPECT_EQ(dem.bonds().tensile_strength_n_per_m(), want.bonds().tensile_strength_n_per_m())
          << entry.path();
      EXPECT_EQ(dem.bonds().normal_stiffness_pa(), rock.dem().bonds().normal_stiffness_pa())
          << entry.path();
      EXPECT_EQ(dem.contact().shear_stiffness_pa(), rock.dem().contact().shear_stiffness_pa())
          << entry.path();
      EXPECT_EQ(dem.density_kg_m3(), rock.dem().density_kg_m3()) << entry.path();
    }
  }
  EXPECT_GE(scenes, 7);
}

}  // namespace
