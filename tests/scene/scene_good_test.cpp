// A correct scene loads, reads back with its defaults, and every case in cases/ loads.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scene/scene_loader.hpp"

namespace {

namespace fs = std::filesystem;
using rockcut::scene::load_scene;
using rockcut::scene::parse_scene;
using rockcut::scene::SceneError;
using testing::HasSubstr;

constexpr const char* kGood = R"(# a comment
title: "block"
time { end_time_s: 0.5 dt_s: 1e-6 }
output { frame_fields: ["position", "velocity"] }
dem {
  density_kg_m3: 2650
  gravity_m_s2 { y: -9.81 }
  lattice { nx: 2 ny: 3 spacing_m: 0.01 radius_m: 0.005 }
}
)";

TEST(SceneGood, ValuesAndDefaultsReadBack) {
  const auto loaded = parse_scene(kGood, "good.pbtxt");
  const rockcut::Scene& s = loaded.scene;
  EXPECT_EQ(s.title(), "block");
  EXPECT_DOUBLE_EQ(s.time().end_time_s(), 0.5);
  EXPECT_DOUBLE_EQ(s.time().dt_s(), 1e-6);
  EXPECT_DOUBLE_EQ(s.time().dt_safety(), 0.2);  // default
  EXPECT_DOUBLE_EQ(s.dem().density_kg_m3(), 2650);
  EXPECT_DOUBLE_EQ(s.dem().gravity_m_s2().x(), 0);
  EXPECT_DOUBLE_EQ(s.dem().gravity_m_s2().y(), -9.81);
  EXPECT_EQ(s.dem().lattice().ny(), 3u);
  EXPECT_EQ(s.output().frame_fields_size(), 2);
  EXPECT_EQ(s.output().timeseries_every_steps(), 100u);  // default
  EXPECT_FALSE(s.has_fluid());  // an absent optional block is no error, even with required children
  EXPECT_DOUBLE_EQ(s.coupling().timeout_s(), 30);
  EXPECT_EQ(loaded.source_text, kGood);
  EXPECT_THAT(loaded.effective_text(), HasSubstr("end_time_s: 0.5"));
}

TEST(SceneGood, LoadsFromFile) {
  const fs::path dir = fs::path(ROCKCUT_TEST_TMP) / "scene";
  fs::create_directories(dir);
  const fs::path path = dir / "good_from_file.pbtxt";
  std::ofstream(path) << kGood;
  const auto loaded = load_scene(path);
  EXPECT_EQ(loaded.path, path);
  EXPECT_EQ(loaded.scene.dem().lattice().nx(), 2u);
}

TEST(SceneGood, MissingFileIsNamed) {
  const fs::path path = fs::path(ROCKCUT_TEST_TMP) / "scene" / "does_not_exist.pbtxt";
  try {
    load_scene(path);
    FAIL() << "a missing file loaded";
  } catch (const SceneError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u);
    EXPECT_THAT(e.what(), HasSubstr(path.string() + ": cannot read the scene file"));
  }
}

TEST(SceneGood, EveryCaseLoads) {
  const fs::path cases = fs::path(ROCKCUT_SOURCE_DIR) / "cases";
  if (!fs::exists(cases)) return;
  for (const auto& entry : fs::recursive_directory_iterator(cases)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".pbtxt") continue;
    // cases/rock/ holds rock descriptions that scenes start from (`base:`), not scenes.
    if (entry.path().parent_path().filename() == "rock") continue;
    SCOPED_TRACE(entry.path().string());
    try {
      load_scene(entry.path());
    } catch (const SceneError& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

}  // namespace
