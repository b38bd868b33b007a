// Random and mutated scenes and --set arguments: the loader answers each with a scene or a
// SceneError whose every line is FILE:LINE:COL: message, never a crash (stack overflow, regular
// expression recursion) and never a quadratic slowdown. Seeded: a failure repeats.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "scene/scene_loader.hpp"

namespace rockcut::scene {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> case_texts() {
  std::vector<std::string> texts;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(ROCKCUT_SOURCE_DIR) / "cases")) {
    // Every case as the run sees it (its bases merged), since a text in memory has no file
    // beside it to compose from.
    if (e.path().extension() != ".pbtxt" || e.path().parent_path().filename() == "base") continue;
    if (e.path().parent_path().filename() == "rock") continue;  // parts, not scenes
    texts.push_back(load_scene(e.path()).effective_text());
  }
  return texts;
}

// Loads `text`; true if it either loaded or was refused with located diagnostics.
::testing::AssertionResult loads_or_is_refused(const std::string& text,
                                               const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, "fuzz.pbtxt", overrides);
    return ::testing::AssertionSuccess();
  } catch (const SceneError& e) {
    for (const Diagnostic& d : e.diagnostics()) {
      if (d.file.empty() || d.message.empty()) {
        return ::testing::AssertionFailure() << "an unlocated diagnostic: " << d.to_string();
      }
    }
    return ::testing::AssertionSuccess();
  }
}

TEST(SceneFuzz, RandomBytesAreRefusedWithLocatedErrors) {
  std::mt19937_64 rng(1);
  for (int k = 0; k < 40; ++k) {
    std::string text(1 + rng() % 20000, '\0');
    for (char& c : text) c = static_cast<char>(rng());
    EXPECT_TRUE(loads_or_is_refused(text)) << "random text " << k;
  }
  std::string mib(1 << 20, '\0');
  for (char& c : mib) c = static_cast<char>(rng());
  EXPECT_TRUE(loads_or_is_refused(mib)) << "1 MiB of random bytes";
}

TEST(SceneFuzz, DeepNestingAndHugeNamesAreRefused) {
  std::string known, unknown;
  for (int k = 0; k < 100000; ++k) known += "dem { ", unknown += "a { ";
  EXPECT_THROW(parse_scene(known, "deep.pbtxt"), SceneError);
  EXPECT_THROW(parse_scene(unknown, "deep.pbtxt"), SceneError);
  EXPECT_THROW(parse_scene(std::string(50000, 'x') + ": 1\n", "name.pbtxt"), SceneError);
  // An error far along a 400,000-character line is located in linear time.
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(parse_scene("title: \"" + std::string(400000, 'x') + "\" zzz: 1\n", "line.pbtxt"),
               SceneError);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(SceneFuzz, MutatedCasesLoadOrAreRefused) {
  const std::vector<std::string> cases = case_texts();
  ASSERT_GE(cases.size(), 20u);
  std::mt19937_64 rng(2);
  const std::string alphabet = "{}<>[]:;,\"'#\n .-+eE0123456789abcdefghijklmnopqrstuvwxyz_/\\";
  for (int k = 0; k < 400; ++k) {
    std::string text = cases[rng() % cases.size()];
    for (int edits = 1 + static_cast<int>(rng() % 8); edits > 0 && !text.empty(); --edits) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 4) {
        case 0: text[at] = alphabet[rng() % alphabet.size()]; break;  // replace
        case 1: text.erase(at, 1 + rng() % 20); break;                // delete
        case 2: text.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
        case 3: text.insert(at, text.substr(rng() % text.size(), rng() % 200)); break;  // splice
      }
    }
    EXPECT_TRUE(loads_or_is_refused(text)) << "mutation " << k;
  }
}

TEST(SceneFuzz, RandomOverridesLoadOrAreRefused) {
  const std::vector<std::string> cases = case_texts();
  std::mt19937_64 rng(3);
  const std::vector<std::string> paths = {
      "time.end_time_s", "time.dt_s", "dem.threads", "dem.tool.velocity_m_s", "coupling.timeout_s",
      "fluid.model", "output.frame_fields", "dem.walls", "nope", "dem..x", ".", "", "dem.specimen",
      "water_depth_m", "dem.bonds.tensile_strength_n_per_m", "output.checkpoint_interval_s"};
  const std::vector<std::string> values = {
      "1", "-1", "0", "1e300", "-1e300", "nan", "inf", "\"x\"", "", "{}", "[1,2]", "true",
      "18446744073709551616", "1e-320", std::string(10000, '9'), "\"" + std::string(5000, 'a')};
  for (int k = 0; k < 400; ++k) {
    std::vector<std::string> overrides;
    for (int n = 1 + static_cast<int>(rng() % 3); n > 0; --n) {
      overrides.push_back(paths[rng() % paths.size()] + (rng() % 8 ? "=" : "") +
                          values[rng() % values.size()]);
    }
    EXPECT_TRUE(loads_or_is_refused(cases[rng() % cases.size()], overrides)) << "overrides " << k;
  }
}

// What validated and then failed at run time: each is now refused with its place in the file.
TEST(SceneRules, NamesAndListsAndTimeoutsAreCheckedBeforeTheRun) {
  const fs::path base =
      fs::path(ROCKCUT_SOURCE_DIR) / "cases" / "cutting" / "saturated_reduced.pbtxt";
  const fs::path file = fs::path(ROCKCUT_TEST_TMP) / "scene_rules.pbtxt";
  fs::create_directories(file.parent_path());
  auto refused = [&](const std::string& extra, const std::vector<std::string>& sets = {}) {
    std::ofstream(file) << "base: \"" << base.string() << "\"\n" << extra << "\n";
    try {
      load_scene(file, sets);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refused("output { frame_fields: [\"radius\", \"radius\"] }").find("is given twice"),
            std::string::npos);
  EXPECT_NE(refused("dem { walls { name: \"a/b\" vertex_m { x: 0 y: 0 } vertex_m { x: 1 y: 0 } } }")
                .find("is not a plain name"),
            std::string::npos);
  // A list written in a scene replaces its base's: two walls of one name in the scene itself.
  const std::string wall = "walls { name: \"floor\" vertex_m { x: 0 y: 0 } vertex_m { x: 1 y: 0 } }";
  EXPECT_NE(refused("dem { " + wall + " " + wall + " }").find("dem.walls[1].name = \"floor\" is given twice"),
            std::string::npos);
  EXPECT_NE(refused("", {"coupling.timeout_s=0"}).find("out of range"), std::string::npos);
  EXPECT_NE(refused("", {"coupling.timeout_s=1e-300"}).find("out of range"), std::string::npos);
  EXPECT_NE(refused("", {"coupling.timeout_s=1e300"}).find("out of range"), std::string::npos);
  EXPECT_EQ(refused(""), "");
}

}  // namespace
}  // namespace rockcut::scene
