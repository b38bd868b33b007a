// Each kind of mistake in a scene file is reported at its FILE:LINE:COL with a useful message.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scene/scene_loader.hpp"

namespace {

namespace fs = std::filesystem;
using rockcut::scene::Diagnostic;
using rockcut::scene::load_scene;
using rockcut::scene::SceneError;
using testing::AllOf;
using testing::HasSubstr;
using testing::StartsWith;

// A valid dem block, for scenes whose mistake is elsewhere.
constexpr const char* kDem = "dem { lattice { nx: 1 ny: 1 spacing_m: 1 radius_m: 0.5 } }\n";

struct Loaded {
  std::string file;
  std::vector<Diagnostic> errors;
  std::string what;
};

// Writes `text` to a file named after the running test and returns what loading it reports.
Loaded load_errors(const std::string& text) {
  const fs::path dir = fs::path(ROCKCUT_TEST_TMP) / "scene";
  fs::create_directories(dir);
  const fs::path path =
      dir / (std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) + ".pbtxt");
  std::ofstream(path) << text;
  try {
    load_scene(path);
  } catch (const SceneError& e) {
    return {path.string(), e.diagnostics(), e.what()};
  }
  ADD_FAILURE() << "the scene loaded without error:\n" << text;
  return {path.string(), {}, ""};
}

// The only problem in `text` is at `position` ("LINE:COL") and its message contains `words`.
template <class... Words>
void expect_one(const std::string& text, const std::string& position, Words... words) {
  const Loaded loaded = load_errors(text);
  ASSERT_EQ(loaded.errors.size(), 1u) << loaded.what;
  EXPECT_THAT(loaded.errors[0].to_string(),
              AllOf(StartsWith(loaded.file + ":" + position + ": "), HasSubstr(words)...));
}

TEST(SceneErrors, SyntaxError) {
  expect_one(std::string("time { end_time_s 1 }\n") + kDem, "1:19", "Expected \":\"");
}

TEST(SceneErrors, UnknownFieldSuggestsNearest) {
  const Loaded loaded = load_errors(std::string("time {\n  end_tme: 1\n}\n") + kDem);
  ASSERT_EQ(loaded.errors.size(), 2u) << loaded.what;  // the typo, and so the missing end_time_s
  EXPECT_EQ(loaded.errors[0].to_string(),
            loaded.file + ":1:1: missing required field \"time.end_time_s\" [s]: Simulated time at "
                          "which the run ends.");
  EXPECT_EQ(loaded.errors[1].to_string(),
            loaded.file + ":2:3: Message type \"rockcut.Time\" has no field named \"end_tme\" "
                          "(did you mean \"end_time_s\"?)");
}

TEST(SceneErrors, UnknownFieldListsNamesWhenNoneIsClose) {
  expect_one(std::string("time { end_time_s: 1 }\n") + kDem + "\tfrobnicate: 3\n", "3:9",
             "has no field named \"frobnicate\"; valid names: title, time, output, dem");
}

TEST(SceneErrors, WrongType) {
  expect_one(std::string("time {\n  end_time_s: \"abc\"\n}\n") + kDem, "2:15", "Expected double",
             "\"abc\"");
}

TEST(SceneErrors, BelowGreaterThan) {
  expect_one(std::string("time { end_time_s: 1 }\ndem {\n  density_kg_m3: -5\n") +
                 "  lattice { nx: 1 ny: 1 spacing_m: 1 radius_m: 0.5 }\n}\n",
             "3:3", "dem.density_kg_m3 = -5 is out of range: must be > 0 [kg/m^3]");
}

TEST(SceneErrors, BelowMin) {
  expect_one(std::string("time { end_time_s: 1 }\n") + kDem + "output { timeseries_every_steps: 0 }\n",
             "3:10", "output.timeseries_every_steps = 0 is out of range: must be >= 1 [steps]");
}

TEST(SceneErrors, AboveMax) {
  expect_one(std::string("time { end_time_s: 1 dt_safety: 1.5 }\n") + kDem, "1:22",
             "time.dt_safety = 1.5 is out of range: must be > 0 and <= 1 [1]");
}

TEST(SceneErrors, NotFinite) {
  expect_one(std::string("time { end_time_s: inf }\n") + kDem, "1:8",
             "time.end_time_s = inf is not a finite number");
}

TEST(SceneErrors, MissingRequiredScalar) {
  expect_one("time { end_time_s: 1 }\ndem {\n  lattice {\n    nx: 1 ny: 1 spacing_m: 1\n  }\n}\n", "3:3",
             "missing required field \"dem.lattice.radius_m\" [m]: Disc radius.");
}

TEST(SceneErrors, MissingRequiredBlock) {
  expect_one(kDem, "1:1",
             "missing required field \"time\": How long to simulate and with which time step.");
}

TEST(SceneErrors, MissingRequiredInsideAPresentOptionalBlock) {
  expect_one(std::string("time { end_time_s: 1 }\n") + kDem + "fluid {}\n", "3:1",
             "missing required field \"fluid.model\"");
}

TEST(SceneErrors, DisallowedChoice) {
  expect_one(std::string("time { end_time_s: 1 }\n") + kDem +
                 "verification { analytical: \"uniform_aceleration\" }\n",
             "3:16",
             "verification.analytical = \"uniform_aceleration\" is not allowed; choose one of: "
             "uniform_acceleration, terzaghi, gaussian_pulse, undrained_step (did you mean "
             "\"uniform_acceleration\"?)");
}

TEST(SceneErrors, DisallowedChoiceInAList) {
  expect_one(std::string("time { end_time_s: 1 }\n") + kDem +
                 "output {\n  frame_fields: [\"position\", \"velocty\"]\n}\n",
             "4:3", "output.frame_fields[1] = \"velocty\" is not allowed", "did you mean \"velocity\"?");
}

TEST(SceneErrors, BlockGivenTwice) {
  expect_one(std::string("time { end_time_s: 1 }\n") + kDem + "time { end_time_s: 2 }\n", "3:1",
             "Non-repeated field \"time\" is specified multiple times");
}

TEST(SceneErrors, AllProblemsReportedTogether) {
  const Loaded loaded = load_errors(
      "time { end_time_s: 1 dt_safety: 2 }\n"
      "dem {\n"
      "  density_kg_m3: 0\n"
      "  lattice { nx: 0 ny: 1 spacing_m: 1 radius_m: 0.5 }\n"
      "}\n"
      "fluid { modl: \"x\" }\n");
  ASSERT_EQ(loaded.errors.size(), 5u) << loaded.what;
  const std::vector<std::pair<std::string, std::string>> expected{
      {"1:22", "time.dt_safety = 2"},
      {"3:3", "dem.density_kg_m3 = 0"},
      {"4:13", "dem.lattice.nx = 0"},
      {"6:1", "missing required field \"fluid.model\""},
      {"6:9", "no field named \"modl\" (did you mean \"model\"?)"}};
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_THAT(loaded.errors[i].to_string(), AllOf(StartsWith(loaded.file + ":" + expected[i].first + ": "),
                                                    HasSubstr(expected[i].second)));
  // what() is every diagnostic, one per line.
  std::string lines;
  for (const Diagnostic& d : loaded.errors) lines.append(lines.empty() ? "" : "\n").append(d.to_string());
  EXPECT_EQ(loaded.what, lines);
}

}  // namespace
