// End-to-end dry cutting: a small, coarse version of cases/cutting/dry_reduced.pbtxt run through
// the real coupler and dem_module. Checks what a cutting run writes, that it is reproducible bit for
// bit for a given seed and thread count, and that bad DEM parameters are refused before anything is
// written.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "integration/h5_read.hpp"
#include "integration/process_helpers.hpp"
#include "integration/small_cuts.hpp"
#include "integration/summary_values.hpp"
#include "output/summary_json.hpp"
#include "support/summary_parser.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;
using coupler::Summary;

// Bad input exits 2 and starts no run, whoever finds it: the scene loader (schema ranges) before any
// process starts, or the DEM when it answers Init with an error (a combination the schema cannot
// check); the coupler then reports "refused by dem_module" (coupler/session/run_session.cpp).
constexpr int kExitBadInput = 2;

// Runs the small cut with extra arguments into a fresh directory.
CouplerRun run_small_cut(const std::string& name, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = kSmallDryCut;
  args.insert(args.end(), extra.begin(), extra.end());
  return run_coupler(kDryReducedScene, args, fresh_dir(name), std::chrono::milliseconds(60000));
}

// Every time series (step is uint64 and follows time_s), /breaks and the last frame's positions of
// two runs, byte for byte.
void expect_bit_identical_runs(const fs::path& a_dir, const fs::path& b_dir) {
  const H5Reader a(a_dir / "run.h5"), b(b_dir / "run.h5");
  const auto names = a.members("/timeseries");
  ASSERT_EQ(names, b.members("/timeseries"));
  ASSERT_NE(std::find(names.begin(), names.end(), "tool_force_x_n_per_m"), names.end());
  for (const std::string& name : names) {
    if (name == "step") continue;
    EXPECT_TRUE(bit_identical(a.doubles("/timeseries/" + name), b.doubles("/timeseries/" + name)))
        << "/timeseries/" << name;
  }
  for (const char* name : {"time_s", "x_m", "y_m", "mode"}) {
    EXPECT_TRUE(bit_identical(a.doubles("/breaks/" + std::string(name)),
                              b.doubles("/breaks/" + std::string(name))))
        << "/breaks/" << name;
  }
  ASSERT_EQ(last_frame(a), last_frame(b));
  const auto pa = a.doubles(last_frame(a) + "/position");
  EXPECT_FALSE(pa.empty());
  EXPECT_TRUE(bit_identical(pa, b.doubles(last_frame(b) + "/position"))) << "final positions";
  EXPECT_TRUE(bit_identical(a.doubles(last_frame(a) + "/damage"),
                            b.doubles(last_frame(b) + "/damage")))
      << "final damage";
}

TEST(Cutting, SmallDryCutWritesForcesBreaksAndDamage) {
  const fs::path dir = fresh_dir("small_cut");
  std::vector<std::string> argv = {bin("coupler"), "run", kDryReducedScene, "--out",
                                   (dir / "out").string()};
  argv.insert(argv.end(), kSmallDryCut.begin(), kSmallDryCut.end());
  const Spawned s = spawn(argv, dir, "coupler");
  KillOnExit guard{s.pid};
  // Watch the coupler's children while it runs: a dry scene starts only a dem_module.
  std::vector<std::string> seen;
  std::optional<int> code;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!(code = wait_exit(s.pid, std::chrono::milliseconds(2))) &&
         std::chrono::steady_clock::now() < deadline) {
    for (pid_t kid : children_of(s.pid)) seen.push_back(command_name(kid));
  }
  ASSERT_TRUE(code.has_value()) << "the small cut did not finish within 60 s";
  ASSERT_EQ(*code, 0) << read_file(s.err_file);
  // A child caught between fork and exec still carries the coupler's name: what matters is that
  // no fluid process ever appears and the DEM does.
  for (const std::string& name : seen) EXPECT_NE(name, "fluid_module");
  EXPECT_NE(std::find(seen.begin(), seen.end(), "dem_module"), seen.end());
  EXPECT_NE(read_file(s.err_file).find("no fluid process"), std::string::npos);

  const fs::path out = dir / "out";
  const Summary summary = coupler::read_summary(out / "summary.json");
  EXPECT_EQ(text(summary, "status"), "completed");
  // Energy budget of the dry cut (DESIGN section 5): the same trapezoid and damping quadrature as
  // the saturated cut, measured 0.3 % there; bound 2 %.
  EXPECT_LT(number(summary, "energy_imbalance_rel"), 0.02);
  EXPECT_EQ(text(summary, "fluid_model"), "none");
  for (const char* key : {"force_horizontal_mean_n_per_m", "force_vertical_mean_n_per_m",
                          "force_horizontal_mean_n", "force_vertical_mean_n", "steady_samples",
                          "steady_after_m", "breaks_tensile", "breaks_shear", "chips",
                          "chip_area_mean_m2", "wall_time_s", "particle_steps_per_s"}) {
    EXPECT_TRUE(summary.get(key).has_value()) << "summary.json lacks " << key;
  }
  EXPECT_EQ(number(summary, "steady_after_m"), 0.004);
  EXPECT_GT(number(summary, "steady_samples"), 0);
  // The rock resists the cut: the mean horizontal force of the rock on the tool points against
  // the cutting direction. Its size is not checked here (docs/record/results_local_damping.md has
  // the numbers).
  EXPECT_GT(number(summary, "force_horizontal_mean_n_per_m"), 0.0);
  EXPECT_TRUE(std::isfinite(number(summary, "force_vertical_mean_n_per_m")));
  // Per metre and on the tool width (0.02 m) are the same number up to the one multiplication.
  EXPECT_DOUBLE_EQ(number(summary, "force_horizontal_mean_n"),
                   number(summary, "force_horizontal_mean_n_per_m") * 0.02);
  const double tensile = number(summary, "breaks_tensile"), shear = number(summary, "breaks_shear");
  EXPECT_GT(tensile + shear, 0);

  const H5Reader h5(out / "run.h5");
  // The tool force series is finite at every sample, and the tool moves forward at 1 m/s.
  const auto fx = h5.doubles("/timeseries/tool_force_x_n_per_m");
  const auto fy = h5.doubles("/timeseries/tool_force_y_n_per_m");
  const auto travel = h5.doubles("/timeseries/tool_travel_m");
  const auto time = h5.doubles("/timeseries/time_s");
  ASSERT_FALSE(fx.empty());
  ASSERT_EQ(fx.size(), fy.size());
  ASSERT_EQ(fx.size(), travel.size());
  ASSERT_EQ(fx.size(), time.size());
  for (std::size_t k = 0; k < fx.size(); ++k) {
    ASSERT_TRUE(std::isfinite(fx[k]) && std::isfinite(fy[k])) << "sample " << k;
  }
  // travel = start (-start_gap, 1 mm) + v t; the tool's offset is accumulated step by step, so
  // allow round-off of 1e-12 m (1e-9 of the travel).
  for (std::size_t k = 0; k < travel.size(); ++k) {
    ASSERT_NEAR(travel[k], -0.001 + 1.0 * time[k], 1e-12) << "sample " << k;
  }
  // The break counts in the summary are those of the last sample, and /breaks holds one row per
  // break.
  EXPECT_EQ(h5.doubles("/timeseries/breaks_tensile").back(), tensile);
  EXPECT_EQ(h5.doubles("/timeseries/breaks_shear").back(), shear);
  const auto mode = h5.doubles("/breaks/mode");
  EXPECT_EQ(static_cast<double>(mode.size()), tensile + shear);
  EXPECT_EQ(h5.doubles("/breaks/x_m").size(), mode.size());
  EXPECT_EQ(static_cast<double>(std::count(mode.begin(), mode.end(), 0.0)), tensile);
  EXPECT_EQ(static_cast<double>(std::count(mode.begin(), mode.end(), 1.0)), shear);

  // Damage in every frame: one value per disc in [0, 1], none at t = 0, some by the end.
  const auto frames = h5.members("/frames");
  ASSERT_GE(frames.size(), 2u);
  for (const std::string& frame : frames) {
    const auto damage = h5.doubles("/frames/" + frame + "/damage");
    ASSERT_EQ(damage.size(), h5.doubles("/frames/" + frame + "/radius").size()) << frame;
    for (double d : damage) {
      ASSERT_TRUE(d >= 0.0 && d <= 1.0) << frame << ": damage " << d;
    }
  }
  const auto d0 = h5.doubles("/frames/" + frames.front() + "/damage");
  EXPECT_TRUE(std::all_of(d0.begin(), d0.end(), [](double d) { return d == 0.0; }));
  const auto d1 = h5.doubles(last_frame(h5) + "/damage");
  EXPECT_TRUE(std::any_of(d1.begin(), d1.end(), [](double d) { return d > 0.0; }));
}

TEST(Cutting, SameSeedOneThreadIsBitIdentical) {
  const CouplerRun a = run_small_cut("repro_1a"), b = run_small_cut("repro_1b");
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  expect_bit_identical_runs(a.out, b.out);
}

TEST(Cutting, SameSeedTwoThreadsIsBitIdentical) {
  // On a busy two-core machine OpenMP's spinning barriers make a 150-disc run with two threads
  // many times slower (measured: 47 s instead of 7 s for 90,000 steps); a passive wait policy
  // changes the timing only, never the arithmetic.
  setenv("OMP_WAIT_POLICY", "passive", 1);
  const CouplerRun a = run_small_cut("repro_2a", {"--set", "dem.threads=2"});
  const CouplerRun b = run_small_cut("repro_2b", {"--set", "dem.threads=2"});
  unsetenv("OMP_WAIT_POLICY");
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  expect_bit_identical_runs(a.out, b.out);
}

TEST(Cutting, AnotherSeedGivesAnotherRun) {
  const CouplerRun a = run_small_cut("seed_1");
  const CouplerRun b = run_small_cut("seed_2", {"--set", "dem.specimen.seed=2"});
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  const H5Reader ha(a.out / "run.h5"), hb(b.out / "run.h5");
  EXPECT_FALSE(bit_identical(ha.doubles(last_frame(ha) + "/position"),
                             hb.doubles(last_frame(hb) + "/position")));
  EXPECT_FALSE(bit_identical(ha.doubles("/timeseries/tool_force_x_n_per_m"),
                             hb.doubles("/timeseries/tool_force_x_n_per_m")));
  // The packing itself differs, not only what happens to it.
  EXPECT_FALSE(bit_identical(ha.doubles("/frames/000000/position"),
                             hb.doubles("/frames/000000/position")));
}

struct BadParameter {
  std::string set;    // the --set argument
  std::string field;  // the field the message must name
};

TEST(Cutting, ARunStoppedBeforeTheSteadyPartWritesNullForItsStatistics) {
  // The small cut's 7 mm of travel never reaches a steady part set at 20 mm: no steady sample, so
  // no steady force, peak or contact share. summary.json says null (read back as NaN), not 0 N/m,
  // and the analytical models' ratios to the DEM's forces are null with them; what the run did
  // measure (breaks, the energy) is still there.
  const CouplerRun r = run_small_cut("no_steady_part", {"--set", "dem.tool.steady_after_m=0.02"});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string json = read_file(r.out / "summary.json");
  EXPECT_NE(json.find("\"force_horizontal_peak_n_per_m\": null"), std::string::npos) << json;
  const Summary s = coupler::read_summary(r.out / "summary.json");
  EXPECT_EQ(number(s, "steady_samples"), 0);
  for (const char* key :
       {"force_horizontal_mean_n_per_m", "force_vertical_mean_n_per_m", "force_horizontal_mean_n",
        "force_horizontal_peak_n_per_m", "force_horizontal_p95_n_per_m",
        "force_horizontal_std_n_per_m", "specific_energy_mpa", "tool_contact_fraction",
        "force_horizontal_mean_in_contact_n_per_m", "analytical_evans_ratio_peak",
        "analytical_evans_ratio_mean"}) {
    EXPECT_TRUE(std::isnan(number(s, key))) << key;
  }
  EXPECT_TRUE(std::isfinite(number(s, "analytical_evans_force_horizontal_n_per_m")));
  EXPECT_GT(number(s, "breaks_tensile") + number(s, "breaks_shear"), 0);
  EXPECT_LT(number(s, "energy_imbalance_rel"), 0.02);
}

TEST(Cutting, BadDemParametersAreRefusedBeforeTheRun) {
  const std::vector<BadParameter> cases = {
      // Each bound alone is valid: only the DEM, when it builds the specimen, sees the pair.
      {"dem.specimen.radius_min_m=0.002", "dem.specimen.radius_min_m"},
      // The schema's range (> 0): refused by the scene loader, before any process starts.
      {"dem.bonds.normal_stiffness_pa=-1", "dem.bonds.normal_stiffness_pa"},
      // The block is about 0.04 m high: a 0.5 m deep cut puts the tip below it.
      {"dem.tool.cutting_depth_m=0.5", "dem.tool.cutting_depth_m"},
  };
  for (const BadParameter& c : cases) {
    const fs::path dir = fresh_dir("bad_" + c.field);
    std::string out, err;
    const int code = run(
        {bin("coupler"), "run", kDryReducedScene, "--out", (dir / "out").string(), "--set", c.set},
        dir, "coupler", &out, &err, std::chrono::milliseconds(30000));
    EXPECT_EQ(code, kExitBadInput) << c.set << "\n" << err;
    EXPECT_NE(err.find(c.field), std::string::npos) << c.set << ": the message names no field\n"
                                                    << err;
    EXPECT_FALSE(fs::exists(dir / "out")) << c.set << ": something was written";
  }
}

}  // namespace
}  // namespace rockcut::test
