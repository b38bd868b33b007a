// --set overrides: applied after parsing, checked like the file, and located at --set:K:COL.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scene/scene_loader.hpp"

namespace {

using rockcut::scene::Diagnostic;
using rockcut::scene::parse_scene;
using rockcut::scene::SceneError;
using testing::AllOf;
using testing::HasSubstr;
using testing::Not;
using testing::StartsWith;

constexpr const char* kScene =
    "time { end_time_s: 1 }\n"
    "dem { lattice { nx: 1 ny: 1 spacing_m: 1 radius_m: 0.5 } }\n";

std::vector<Diagnostic> errors_of(const std::vector<std::string>& overrides) {
  try {
    parse_scene(kScene, "scene.pbtxt", overrides);
  } catch (const SceneError& e) {
    return e.diagnostics();
  }
  ADD_FAILURE() << "the overrides were accepted";
  return {};
}

template <class... Words>
void expect_override_error(const std::vector<std::string>& overrides, const std::string& prefix,
                           Words... words) {
  const std::vector<Diagnostic> errors = errors_of(overrides);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_THAT(errors[0].to_string(), AllOf(StartsWith(prefix), HasSubstr(words)...));
}

TEST(SceneOverrides, ChangeValuesAndShowInEffectiveText) {
  const auto loaded = parse_scene(kScene, "scene.pbtxt",
                                  {"time.end_time_s=2.5", "dem.lattice.nx = 4", "title=two words",
                                   R"(dem.executable="/opt/dem \"x\"")"});
  EXPECT_DOUBLE_EQ(loaded.scene.time().end_time_s(), 2.5);
  EXPECT_EQ(loaded.scene.dem().lattice().nx(), 4u);
  EXPECT_EQ(loaded.scene.title(), "two words");
  EXPECT_EQ(loaded.scene.dem().executable(), "/opt/dem \"x\"");
  EXPECT_EQ(loaded.overrides.size(), 4u);
  EXPECT_THAT(loaded.effective_text(), AllOf(HasSubstr("end_time_s: 2.5"), HasSubstr("nx: 4")));
  EXPECT_THAT(loaded.source_text, Not(HasSubstr("2.5")));
}

TEST(SceneOverrides, CreatesAnAbsentBlock) {
  const auto loaded = parse_scene(kScene, "scene.pbtxt", {"coupling.timeout_s=5"});
  ASSERT_TRUE(loaded.scene.has_coupling());
  EXPECT_DOUBLE_EQ(loaded.scene.coupling().timeout_s(), 5);
  EXPECT_THAT(loaded.effective_text(), HasSubstr("coupling {\n  timeout_s: 5\n}"));
}

TEST(SceneOverrides, BlockCreatedByAnOverrideIsValidatedThere) {
  expect_override_error({"fluid.prescribed_gradient.pressure_gradient_pa_m.x=1"},
                        "--set:1:1: ", "missing required field \"fluid.model\"");
}

TEST(SceneOverrides, UnknownPathSuggestsNearest) {
  expect_override_error({"time.end_time_s=2", "time.end_tme=2"}, "--set:2:6: ",
                        "unknown field \"time.end_tme\" (did you mean \"time.end_time_s\"?)");
  expect_override_error({"frobnicate=1"},
                        "--set:1:1: ", "unknown field \"frobnicate\"; valid names: title, time");
}

TEST(SceneOverrides, BadValues) {
  expect_override_error({"dem.density_kg_m3=abc"}, "--set:1:19: ", "\"abc\" is not a valid double");
  expect_override_error({"dem.lattice.nx=-3"}, "--set:1:16: ", "\"-3\" is not a valid uint32");
  expect_override_error({"dem.lattice.nx=1.5"}, "--set:1:16: ", "not a valid uint32");
  expect_override_error({"title=\"unterminated"}, "--set:1:7: ", "unterminated quoted string");
}

TEST(SceneOverrides, TargetsThatAreNotSingleValues) {
  expect_override_error({"output.frame_fields=position"}, "--set:1:8: ", "repeated field");
  expect_override_error({"dem.lattice=3"}, "--set:1:5: ", "\"dem.lattice\" is a block",
                        "dem.lattice.nx");
  expect_override_error({"time.end_time_s.x=1"},
                        "--set:1:17: ", "\"time.end_time_s\" is a double, not a block");
  expect_override_error({"time..end_time_s=1"}, "--set:1:6: ", "empty field name");
  expect_override_error({"time.end_time_s"}, "--set:1:1: ", "expected dotted.path=value");
}

TEST(SceneOverrides, OutOfRangeIsLocatedAtTheOverride) {
  expect_override_error({"title=x", "dem.density_kg_m3=-1"}, "--set:2:19: ",
                        "dem.density_kg_m3 = -1 is out of range: must be > 0 [kg/m^3]");
}

TEST(SceneOverrides, FileErrorsAndOverrideErrorsTogether) {
  try {
    parse_scene("time { end_time_s: -1 }\n", "scene.pbtxt", {"dem.lattice.nx=0"});
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    // File problems first (in file order), then the overrides.
    // dem and dem.lattice are created by the override: lattice lacks ny, spacing_m and radius_m.
    ASSERT_EQ(e.diagnostics().size(), 5u) << e.what();
    EXPECT_THAT(e.diagnostics()[0].to_string(), StartsWith("scene.pbtxt:1:8: time.end_time_s = -1"));
    EXPECT_THAT(e.diagnostics()[4].to_string(), StartsWith("--set:1:16: dem.lattice.nx = 0"));
  }
}

}  // namespace
