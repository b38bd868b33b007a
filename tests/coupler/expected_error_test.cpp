// The expected error printed at start-up: the model reads the work-precision study's table
// (coupler/data/expected_error.csv, beside the program as share/rockcut/expected_error.csv),
// interpolates in its ladders and refuses to extrapolate beyond the coarsest setting studied. The
// checks take their numbers from that file, not from a copy of it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "observers/expected_error.hpp"
#include "scene/scene_loader.hpp"

namespace rockcut::coupler {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

const fs::path kTable = fs::path(ROCKCUT_SOURCE_DIR) / "coupler" / "data" / "expected_error.csv";

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The settings at each ladder's finest, with one of them replaced.
CutSettings finest(const ErrorModel& m) {
  return {m.dt_safety.back().value, m.fluid_step_ratio.back().value, m.h_per_diameter.back().value,
          m.size_scale.back().value};
}

TEST(ExpectedError, TheProgramsCopyOfTheTableIsTheStudys) {
  // The coupler reads it beside itself (bin/../share/rockcut), as an installation lays it out.
  const fs::path copy = error_model_path(fs::path(ROCKCUT_BIN_DIR));
  EXPECT_EQ(copy, fs::path(ROCKCUT_BIN_DIR).parent_path() / "share" / "rockcut" / "expected_error.csv");
  EXPECT_EQ(read(copy), read(kTable));
}

TEST(ExpectedError, EverySettingOfTheTableGivesItsError) {
  const ErrorModel m = *read_error_model(kTable);
  EXPECT_GE(m.dt_safety.size(), 3u);
  EXPECT_GE(m.fluid_step_ratio.size(), 3u);
  // One ladder at a time away from its finest: the result is that ladder's own error.
  for (const LadderPoint& p : m.dt_safety) {
    CutSettings s = finest(m);
    s.dt_safety = p.value;
    EXPECT_NEAR(*expected_force_error(m, s, nullptr),
                std::hypot(p.force_error, m.fluid_step_ratio.back().force_error,
                           std::hypot(m.h_per_diameter.back().force_error,
                                      m.size_scale.back().force_error)),
                1e-12);
  }
  for (const LadderPoint& p : m.fluid_step_ratio) {
    CutSettings s = finest(m);
    s.fluid_step_ratio = p.value;
    std::string detail;
    const double e = *expected_force_error(m, s, &detail);
    EXPECT_NEAR(e, std::hypot(p.force_error, m.dt_safety.back().force_error,
                              std::hypot(m.h_per_diameter.back().force_error,
                                         m.size_scale.back().force_error)),
                1e-12)
        << detail;
  }
}

TEST(ExpectedError, InterpolatesLinearlyInTheLogAndCombinesByRootSumSquare) {
  const ErrorModel m = *read_error_model(kTable);
  const auto only = [&](auto field, double value) {
    CutSettings s = finest(m);
    s.*field = value;
    return *expected_force_error(m, s, nullptr);
  };
  const LadderPoint a = m.fluid_step_ratio[1], b = m.fluid_step_ratio[2];
  ASSERT_NE(a.force_error, b.force_error);  // so that the midpoint tells interpolation from a step
  const double finest_rest = std::hypot(m.dt_safety.back().force_error,
                                        std::hypot(m.h_per_diameter.back().force_error,
                                                   m.size_scale.back().force_error));
  const double mid = only(&CutSettings::fluid_step_ratio, std::sqrt(a.value * b.value));
  EXPECT_NEAR(mid, std::hypot(0.5 * (a.force_error + b.force_error), finest_rest), 1e-12);
  // Two ladders away from their finest: the root sum square of their errors.
  CutSettings s = finest(m);
  s.dt_safety = m.dt_safety.front().value;
  s.size_scale = m.size_scale.front().value;
  EXPECT_NEAR(*expected_force_error(m, s, nullptr),
              std::hypot(m.dt_safety.front().force_error, m.size_scale.front().force_error,
                         std::hypot(m.fluid_step_ratio.back().force_error,
                                    m.h_per_diameter.back().force_error)),
              1e-12);
}

TEST(ExpectedError, CoarserThanTheStudyIsNotCoveredAndFinerGetsTheFinest) {
  const ErrorModel m = *read_error_model(kTable);
  CutSettings s = finest(m);
  s.dt_safety = 2 * m.dt_safety.front().value;
  std::string detail;
  EXPECT_FALSE(expected_force_error(m, s, &detail).has_value());
  EXPECT_THAT(detail, HasSubstr("dt_safety = " ));
  EXPECT_THAT(detail, HasSubstr("coarser than the study covers"));
  s = finest(m);
  s.size_scale = 2 * m.size_scale.front().value;
  EXPECT_FALSE(expected_force_error(m, s, &detail).has_value());
  EXPECT_THAT(detail, HasSubstr("disc size"));
  // Finer than the study on every ladder (paper-scale discs): below what it resolves.
  const CutSettings fine = {0.5 * m.dt_safety.back().value, 0.5 * m.fluid_step_ratio.back().value,
                            0.5 * m.h_per_diameter.back().value, 0.5 * m.size_scale.back().value};
  EXPECT_EQ(*expected_force_error(m, fine, nullptr), *expected_force_error(m, finest(m), nullptr));
}

TEST(ExpectedError, ABadTableIsNamedWithItsLine) {
  const fs::path dir = fs::path(ROCKCUT_TEST_TMP) / "expected_error";
  fs::create_directories(dir);
  const auto error_of = [&](const std::string& text) {
    const fs::path csv = dir / "table.csv";
    std::ofstream(csv) << text;
    try {
      read_error_model(csv);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string good = "dt_safety,0.4,0.1\ndt_safety,0.2,0\nfluid_step_ratio,1,0.5\n"
                           "fluid_step_ratio,0.5,0\nh_per_diameter,3,0.1\nh_per_diameter,2,0\n"
                           "size_scale,1,0.1\nsize_scale,0.5,0\n";
  EXPECT_EQ(error_of("# comment\nladder,value,force_error\n" + good), "no error");
  EXPECT_THAT(error_of("ladder,value,force_error\ndt_safety,0.4,x\n"),
              HasSubstr("table.csv:2: force_error \"x\" is not a number"));
  EXPECT_THAT(error_of("ladder,value,force_error\ndt_safty,0.4,0.1\n"),
              HasSubstr("table.csv:2: unknown ladder \"dt_safty\""));
  EXPECT_THAT(error_of("ladder,value,force_error\ndt_safety,0.2,0.1\ndt_safety,0.4,0\n"),
              HasSubstr("table.csv:3: dt_safety: settings go from the coarsest"));
  EXPECT_THAT(error_of("ladder,value\n"), HasSubstr("table.csv:1: the header must name"));
  EXPECT_THAT(error_of("ladder,value,force_error\ndt_safety,0.4,0.1\n"),
              HasSubstr("needs two settings or more"));
  EXPECT_THAT(error_of(""), HasSubstr("the header must name"));
  // The damping and force columns: each damping model's rows are a model of their own.
  const std::string viscous =
      "dt_safety,0.4,0.2,viscous,peak\ndt_safety,0.2,0,viscous,peak\n"
      "fluid_step_ratio,1,0.3,viscous,peak\nfluid_step_ratio,0.3,0,viscous,peak\n"
      "h_per_diameter,3,0.1,viscous,peak\nh_per_diameter,2,0,viscous,peak\n"
      "size_scale,1,0.1,viscous,peak\nsize_scale,0.5,0,viscous,peak\n";
  std::string local_rows;
  for (std::size_t at = 0, end; (end = good.find('\n', at)) != std::string::npos; at = end + 1)
    local_rows += good.substr(at, end - at) + ",local,mean\n";
  const fs::path both = dir / "both.csv";
  std::ofstream(both) << "ladder,value,force_error,damping,force\n" + local_rows + viscous;
  const std::optional<ErrorModel> peak = read_error_model(both, "viscous");
  ASSERT_TRUE(peak.has_value());
  EXPECT_EQ(peak->force, "peak");
  EXPECT_EQ(peak->dt_safety.front().force_error, 0.2);
  EXPECT_EQ(read_error_model(both, "local")->force, "mean");
  EXPECT_EQ(read_error_model(both, "local")->dt_safety.front().force_error, 0.1);
  std::vector<std::string> studied;
  EXPECT_FALSE(read_error_model(both, "none", &studied).has_value());
  EXPECT_EQ(studied, (std::vector<std::string>{"local", "viscous"}));
  EXPECT_THAT(error_of("ladder,value,force_error,damping,force\ndt_safety,0.4,0.1,local,max\n"),
              HasSubstr("table.csv:2: unknown force \"max\": mean or peak"));
  EXPECT_THAT(error_of("ladder,value,force_error,damping,force\ndt_safety,0.4,0.1,local,mean\n"
                       "dt_safety,0.2,0,local,peak\n"),
              HasSubstr("table.csv:3: force \"peak\" where the rows of damping \"local\" before it "
                        "have \"mean\""));
  // The fluid_force column: only the lag's ladder may depend on it.
  EXPECT_THAT(error_of("ladder,value,force_error,fluid_force\ndt_safety,0.4,0.1,extrapolated\n"),
              HasSubstr("table.csv:2: fluid_force \"extrapolated\" on the ladder dt_safety: only "
                        "fluid_step_ratio depends on it"));
  EXPECT_THAT(error_of("ladder,value,force_error,fluid_force\ndt_safety,0.4,0.1,implicit\n"),
              HasSubstr("table.csv:2: unknown fluid_force \"implicit\": held, extrapolated or "
                        "extrapolated+passivity"));
  const fs::path forces = dir / "forces.csv";
  std::string held_rows;
  for (std::size_t at = 0, end; (end = good.find('\n', at)) != std::string::npos; at = end + 1)
    held_rows += good.substr(at, end - at) + ",held\n";
  std::ofstream(forces) << "ladder,value,force_error,fluid_force\n" + held_rows +
                               "fluid_step_ratio,1,0.02,extrapolated\n"
                               "fluid_step_ratio,0.2,0,extrapolated\n";
  EXPECT_EQ(read_error_model(forces, "local", nullptr, "held")->fluid_step_ratio.front().force_error,
            0.5);
  const std::optional<ErrorModel> line = read_error_model(forces, "local", nullptr, "extrapolated");
  ASSERT_EQ(line->fluid_step_ratio.size(), 2u);
  EXPECT_EQ(line->fluid_step_ratio.front().force_error, 0.02);
  EXPECT_EQ(line->dt_safety.front().force_error, 0.1);  // the held rows serve both
  std::ofstream(forces) << "ladder,value,force_error\n" + good;
  const std::optional<ErrorModel> unstudied = read_error_model(forces, "local", nullptr, "extrapolated");
  ASSERT_TRUE(unstudied.has_value());
  EXPECT_TRUE(unstudied->fluid_step_ratio.empty());
  std::string why;
  EXPECT_FALSE(expected_force_error(*unstudied, {0.2, 0.5, 2.0, 0.5}, &why).has_value());
  EXPECT_THAT(why, HasSubstr("no measurement with this coupling.fluid_force and lag_correction"));
  const fs::path missing = dir / "none.csv";
  try {
    read_error_model(missing);
    ADD_FAILURE() << "read a missing file";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("none.csv:0: cannot read the accuracy study's table"));
  }
}

TEST(ExpectedError, TheStartUpLineOfTheDefaultSceneAndWithoutTheTable) {
  // The default scene at the study's default settings: dt_safety 0.2 of the DEM limit, N = 3 at
  // 0.0705 of the stiffness limit per step, h / diameter 2.5, the study's disc size.
  const auto loaded = rockcut::scene::load_scene(fs::path(ROCKCUT_SOURCE_DIR) / "cases" / "cutting" /
                                                 "saturated_reduced.pbtxt");
  TimePlan plan;
  plan.dt_s = 1e-7;
  plan.coupling_interval = 3;
  const double dem_limit_s = 5e-7, stiffness_limit_s = 1e-7 / 0.0705;
  const auto line = expected_error_line(loaded.scene, plan, dem_limit_s, stiffness_limit_s,
                                        ROCKCUT_BIN_DIR);
  ASSERT_TRUE(line.has_value());
  const ErrorModel m = *read_error_model(kTable);
  const double e = *expected_force_error(m, {0.2, 3 * 0.0705, 2.5, 1.0}, nullptr);
  EXPECT_THAT(*line, HasSubstr("expected error of the mean horizontal force about " +
                               std::to_string(static_cast<int>(std::lround(100 * e))) + " %"));
  // A program without the table beside it says so and goes on.
  const fs::path lonely = fs::path(ROCKCUT_TEST_TMP) / "expected_error" / "no_table" / "bin";
  fs::create_directories(lonely);
  const auto without = expected_error_line(loaded.scene, plan, dem_limit_s, stiffness_limit_s, lonely);
  ASSERT_TRUE(without.has_value());
  EXPECT_THAT(*without, HasSubstr("accuracy   no estimate: "));
  EXPECT_THAT(*without, HasSubstr("share/rockcut/expected_error.csv:0: cannot read"));
}

TEST(ExpectedError, EachDampingModelHasItsOwnStudyAndForce) {
  // The dynamic cut under dashpots is read by its peak force, and the study measured that.
  const auto dynamic = rockcut::scene::load_scene(fs::path(ROCKCUT_SOURCE_DIR) / "cases" /
                                                  "cutting" /
                                                  "saturated_reduced_long_viscous.pbtxt");
  ASSERT_EQ(dynamic.scene.dem().damping().model(), "viscous");
  const std::optional<ErrorModel> m = read_error_model(kTable, "viscous");
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->force, "peak");
  TimePlan plan;
  plan.dt_s = 1e-7;
  plan.coupling_interval = 1;
  const double dem_limit_s = 5e-7, stiffness_limit_s = 3e-7;
  const auto line = expected_error_line(dynamic.scene, plan, dem_limit_s, stiffness_limit_s,
                                        ROCKCUT_BIN_DIR);
  ASSERT_TRUE(line.has_value());
  const double h_per_diameter = dynamic.scene.fluid().smoothing_length_m() /
                                (dynamic.scene.dem().specimen().radius_min_m() +
                                 dynamic.scene.dem().specimen().radius_max_m());
  const double e = *expected_force_error(*m, {0.2, 0.0, h_per_diameter, 1.0}, nullptr);
  EXPECT_THAT(*line, HasSubstr("expected error of the peak horizontal force about " +
                               std::to_string(static_cast<int>(std::lround(100 * e))) + " %"));
  // The scene's own coupling, the force extrapolated at N = 4 (0.803 of its limit, read as the
  // limit itself): the lag's part is its own ladder's.
  ASSERT_EQ(dynamic.scene.coupling().fluid_force(), "extrapolated");
  TimePlan extrapolated = plan;
  extrapolated.coupling_interval = 4;
  extrapolated.extrapolate_fluid_force = true;
  const double extrapolated_limit_s = 4 * plan.dt_s / 0.803;
  const auto line4 = expected_error_line(dynamic.scene, extrapolated, dem_limit_s,
                                         extrapolated_limit_s, ROCKCUT_BIN_DIR);
  ASSERT_TRUE(line4.has_value());
  const std::optional<ErrorModel> m4 = read_error_model(kTable, "viscous", nullptr, "extrapolated");
  ASSERT_TRUE(m4.has_value());
  std::string detail;
  const double e4 = *expected_force_error(*m4, {0.2, 0.803, h_per_diameter, 1.0}, &detail);
  EXPECT_THAT(detail, HasSubstr("2 % from fluid step / stiffness limit 0.803"));
  EXPECT_THAT(*line4, HasSubstr("about " + std::to_string(static_cast<int>(std::lround(100 * e4))) +
                                " %"));
  // A damping model the study did not measure is named, with those it did.
  rockcut::Scene undamped = dynamic.scene;
  undamped.mutable_dem()->mutable_damping()->set_model("none");
  const auto none = expected_error_line(undamped, plan, dem_limit_s, stiffness_limit_s,
                                        ROCKCUT_BIN_DIR);
  ASSERT_TRUE(none.has_value());
  EXPECT_THAT(*none, HasSubstr("it measured dem.damping.model \"local\", \"viscous\", not \"none\""));
}

}  // namespace
}  // namespace rockcut::coupler
