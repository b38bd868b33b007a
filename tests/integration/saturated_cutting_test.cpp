// End-to-end saturated cutting: a small, coarse version of cases/cutting/saturated_reduced.pbtxt
// through the real coupler, dem_module and fluid_module. Checks what a coupled cutting run writes
// (pressure nodes, Peclet regime, the coupling interval and its binding limit, the modules' busy
// times, no flux at the tool and walls), and that the fluid model is swapped by one scene line or
// replaced by an executable given by path, the DEM untouched.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "integration/h5_read.hpp"
#include "integration/process_helpers.hpp"
#include "integration/summary_values.hpp"
#include "output/summary_json.hpp"
#include "support/summary_parser.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;
using coupler::Summary;

// saturated_reduced.pbtxt with the node boxes 10 mm wide (written once per test directory): a scene
// that starts from it (`base:`) and names the three nodes again (a repeated field replaces the
// base's list).
fs::path small_scene(const fs::path& dir) {
  const fs::path scene = dir / "saturated_small.pbtxt";
  std::ofstream(scene) << "base: \"" << source("cases/cutting/saturated_reduced.pbtxt") << "\"\n"
                       << "dem { tool {\n"
                          "  pressure_nodes { name: \"p1\" size_m: 0.01 }\n"
                          "  pressure_nodes { name: \"p2\" offset_m { x: 0.0125 y: 0.01 } size_m: 0.01 }\n"
                          "  pressure_nodes { name: \"p3\" offset_m { x: 0.03 } size_m: 0.01 }\n"
                          "} }\n";
  return scene;
}

// Twice as coarse as saturated_reduced (radius 1.6-3.2 mm, about 150 discs, h 12 mm: the same
// h / diameter), 7 mm of travel with the steady part from 4 mm, and node boxes of 10 mm so each
// holds a few disc centres. Under two seconds with one thread.
const std::vector<std::string> kSmallSaturatedCut = {
    "--set", "dem.specimen.radius_min_m=0.0016", "--set", "dem.specimen.radius_max_m=0.0032",
    "--set", "fluid.smoothing_length_m=0.012",   "--set", "time.end_time_s=0.008",
    "--set", "dem.tool.steady_after_m=0.004",    "--set", "output.frame_interval_s=0.004"};

CouplerRun run_small_cut(const std::string& name, const std::vector<std::string>& extra = {}) {
  const fs::path dir = fresh_dir(name);
  std::vector<std::string> args = kSmallSaturatedCut;
  args.insert(args.end(), extra.begin(), extra.end());
  return run_coupler(small_scene(dir).string(), args, dir, std::chrono::milliseconds(90000));
}

void expect_coupled_cutting_summary(const Summary& s, const std::string& model) {
  EXPECT_EQ(text(s, "status"), "completed");
  EXPECT_EQ(text(s, "fluid_model"), model);
  EXPECT_EQ(text(s, "coupling_scheme"), "half-step exchange");
  for (const char* key :
       {"force_horizontal_mean_n_per_m", "force_vertical_mean_n_per_m", "breaks_tensile",
        "breaks_shear", "chips", "pressure_p1_mean_pa", "pressure_p2_mean_pa",
        "pressure_p3_mean_pa", "peclet_number", "regime", "dt_s", "coupling_interval",
        "wall_time_s", "particle_steps_per_s", "hydrostatic_pressure_pa", "dem_busy_s",
        "fluid_busy_s", "dem_after_reply_s", "fluid_after_reply_s"}) {
    EXPECT_TRUE(s.get(key).has_value()) << "summary.json lacks " << key;
  }
  // Eq. 2: v_c t_c / (4 D) = 1 m/s * 0.02 m / (4 * 2e9 * 1e-14 / 1e-3 m^2/s) = 0.25, transient.
  EXPECT_NEAR(number(s, "peclet_number"), 0.25, 1e-12);
  EXPECT_EQ(text(s, "regime"), "transient");
  EXPECT_GT(number(s, "force_horizontal_mean_n_per_m"), 0.0);
  // The tip node sits in the crushed zone: it holds disc centres in the steady part.
  EXPECT_GT(number(s, "pressure_p1_samples"), 0);
  EXPECT_TRUE(std::isfinite(number(s, "pressure_p1_mean_pa")));
  EXPECT_GT(number(s, "fluid_busy_s"), 0.0);
  EXPECT_GT(number(s, "dem_busy_s"), 0.0);
  EXPECT_LE(number(s, "dem_busy_s"), number(s, "wall_time_s") * 1.05);
  // The DEM computes its contact forces after replying with the kinematics (DESIGN section 3),
  // a part of its busy time. The fluid does nothing after its replies: its share is the two clock
  // reads around an empty call, 0.2 ms over this run on a quiet host, but on a loaded one the
  // scheduler may park the process between them just as the DEM wakes on the reply (9 ms against
  // 7 ms of busy time, seen under ctest -j2), so only its sign is a property of the code.
  EXPECT_GT(number(s, "dem_after_reply_s"), 0.0);
  EXPECT_LT(number(s, "dem_after_reply_s"), number(s, "dem_busy_s"));
  EXPECT_GE(number(s, "fluid_after_reply_s"), 0.0);
  // The energy budget (DESIGN section 5): tool and wall work + fluid work = kinetic + strain +
  // damping + friction + broken bonds. Its terms are time integrals by the trapezoid rule over a
  // step, the damping's with the O(dt) error of a force that flips sign with v; measured 0.3-0.9 %
  // on the reduced cut (0 m and 2000 m, seeds 1-3). Bound: 2 %, twice the largest measured.
  EXPECT_LT(number(s, "energy_imbalance_rel"), 0.02);
  // The ledger's terms in summary.json balance to within that imbalance (the specimen starts at
  // rest and at zero stress, so nothing is given but work).
  const double work = number(s, "boundary_work_j") + number(s, "external_work_j") +
                      number(s, "gravity_work_j");
  const double held = number(s, "damping_j") + number(s, "friction_j") +
                      number(s, "broken_bond_j") + number(s, "kinetic_energy_j") +
                      number(s, "strain_energy_j");
  EXPECT_GT(number(s, "boundary_work_j"), 0.0);
  EXPECT_NEAR(work, held, 0.02 * number(s, "boundary_work_j"));
  // Local damping takes most of the tool's work: 74-83 % in 28 runs of the reduced cut at 0 m
  // (docs/accuracy.md). Bound: above a half.
  EXPECT_GT(number(s, "damping_j"), 0.5 * number(s, "boundary_work_j"));
}

TEST(SaturatedCutting, ExplicitModelWritesPressureNodesRegimeAndSealsAtTheTool) {
  const CouplerRun r = run_small_cut("explicit");
  ASSERT_EQ(r.code, 0) << r.err;
  const Summary s = coupler::read_summary(r.out / "summary.json");
  expect_coupled_cutting_summary(s, "explicit");
  // N is chosen from the limits and its binding limit printed: here the pore fluid's stiffness
  // (lagged force) binds, well below the explicit diffusion limit.
  EXPECT_GT(number(s, "coupling_interval"), 1);
  EXPECT_NE(r.err.find("binding: pore_fluid_stiffness"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("transient regime"), std::string::npos) << r.err;

  const H5Reader h5(r.out / "run.h5");
  for (const char* name : {"fluid_probe_p1_pa", "fluid_probe_p2_pa", "fluid_probe_p3_pa",
                           "fluid_probe_p1_particles", "tool_tip_x_m"}) {
    EXPECT_FALSE(h5.doubles(std::string("/timeseries/") + name).empty()) << name;
  }
  // No side of the box is sealed in this scene: the sealed particles (boundary 2) are those
  // facing the floor, the walls and the tool, whose segments the DEM sends every exchange.
  const auto boundary = h5.doubles(last_frame(h5) + "/boundary");
  const auto sealed = std::count(boundary.begin(), boundary.end(), 2.0);
  const auto drained = std::count(boundary.begin(), boundary.end(), 1.0);
  EXPECT_GT(sealed, 0);
  EXPECT_GT(drained, 0);
}

TEST(SaturatedCutting, ImplicitModelByOneSceneLine) {
  const CouplerRun r = run_small_cut("implicit", {"--set", "fluid.model=implicit"});
  ASSERT_EQ(r.code, 0) << r.err;
  expect_coupled_cutting_summary(coupler::read_summary(r.out / "summary.json"), "implicit");
}

TEST(SaturatedCutting, FluidExecutableGivenByPath) {
  // A fluid module elsewhere on disk (here a copy under another name) runs in place of the built
  // in one; a path that does not exist is named in the error.
  const fs::path dir = fresh_dir("fluid_exe");
  const fs::path exe = dir / "my_fluid_model";
  fs::copy_file(bin("fluid_module"), exe);
  const CouplerRun r = run_small_cut("by_path", {"--set", "fluid.executable=" + exe.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  expect_coupled_cutting_summary(coupler::read_summary(r.out / "summary.json"), "explicit");
  EXPECT_NE(r.err.find("my_fluid_model"), std::string::npos) << r.err;

  const CouplerRun bad = run_small_cut("bad_path", {"--set", "fluid.executable=/nonexistent/fluid"});
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.err.find("/nonexistent/fluid"), std::string::npos) << bad.err;
}

TEST(SaturatedCutting, CouplingIntervalAboveTheFluidStiffnessLimitIsRefused) {
  const CouplerRun r = run_small_cut("too_large_n", {"--set", "coupling.interval=100000"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("pore_fluid_stiffness"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("use coupling.interval <="), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(r.out / "summary.json"));
}

// The fluid's stiffness limit C alpha_d sqrt(m_min / (alpha M)) takes the grain density the DEM
// reports (InitReply.solid, forwarded by the coupler in the fluid's Init), not the scene's: a DEM
// that reports 4 times the density (rogue_module heavy_grains, the real DEM otherwise) doubles it.
// Both runs are refused at once (an N far above the limit), naming the limit with 4 significant
// digits, each within 5e-4 relative: the ratio is 2 within 1e-3 relative.
TEST(SaturatedCutting, TheFluidStiffnessLimitFollowsTheDensityTheDemReports) {
  auto stiffness_limit_s = [](const std::string& err) {
    const std::string key = "limit pore_fluid_stiffness (";
    const std::size_t at = err.find(key);
    return at == std::string::npos ? -1.0 : std::stod(err.substr(at + key.size()));
  };
  const CouplerRun own = run_small_cut("density_own", {"--set", "coupling.interval=100000"});
  EXPECT_EQ(own.code, 2) << own.err;
  setenv("ROCKCUT_ROGUE_MODE", "heavy_grains", 1);
  const CouplerRun heavy = run_small_cut(
      "density_heavy", {"--set", "coupling.interval=100000", "--set",
                        "dem.executable=" + std::string(ROCKCUT_BIN_DIR) + "/../tests/rogue_module"});
  unsetenv("ROCKCUT_ROGUE_MODE");
  EXPECT_EQ(heavy.code, 2) << heavy.err;
  const double dt_own = stiffness_limit_s(own.err), dt_heavy = stiffness_limit_s(heavy.err);
  ASSERT_GT(dt_own, 0.0) << own.err;
  EXPECT_NEAR(dt_heavy / dt_own, 2.0, 2.0 * 1e-3) << heavy.err;
}

TEST(SaturatedCutting, WithoutDampingTheFluidForceDoesNotLag) {
  // The lagged force is a negative damping that only local damping removes: undamped, N = 1.
  const CouplerRun r = run_small_cut("undamped", {"--set", "dem.damping.model=none",
                                              "--set", "time.end_time_s=0.002"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(number(coupler::read_summary(r.out / "summary.json"), "coupling_interval"), 1);
}

TEST(SaturatedCutting, ForcesRidingOnTheNextAdvanceChangeNoBit) {
  // Between output steps the coupler sends the fluid force with the next Advance instead of a
  // separate ApplyForces (two round trips per exchange instead of three). The DEM does the same
  // arithmetic in the same order, so the state must be bit for bit that of a run which records
  // every step (and so completes every exchange with its own ApplyForces). The same with the
  // fluid's force extrapolated between exchanges (coupling.fluid_force): the line's rate is taken
  // when the force arrives, with the Advance or on its own; and with each grain's own fluid
  // stiffness (coupling.fluid_stiffness "self"), whose array rides with the force.
  for (const std::string variant : {"held", "extrapolated", "self"}) {
    SCOPED_TRACE(variant);
    const std::string fluid_force = variant == "held" ? "held" : "extrapolated";
    std::vector<std::string> short_cut = {
        "--set", "time.end_time_s=0.002", "--set", "output.frame_interval_s=0",
        "--set", "coupling.interval=3",   "--set", "coupling.fluid_force=" + fluid_force};
    if (variant == "self") short_cut.insert(short_cut.end(), {"--set", "coupling.fluid_stiffness=self"});
    std::vector<std::string> sparse = short_cut, dense = short_cut;
    sparse.insert(sparse.end(), {"--set", "output.timeseries_every_steps=100000"});
    dense.insert(dense.end(), {"--set", "output.timeseries_every_steps=1"});
    const CouplerRun a = run_small_cut("merged_sparse_" + variant, sparse);
    const CouplerRun b = run_small_cut("merged_dense_" + variant, dense);
    ASSERT_EQ(a.code, 0) << a.err;
    ASSERT_EQ(b.code, 0) << b.err;
    if (fluid_force == "extrapolated") {
      EXPECT_NE(a.err.find("the DEM extrapolates the fluid's force"), std::string::npos) << a.err;
    }
    EXPECT_EQ(a.err.find("each grain's own pore-fluid stiffness") != std::string::npos,
              variant == "self")
        << a.err;
    const H5Reader ha(a.out / "run.h5"), hb(b.out / "run.h5");
    const auto ta = ha.doubles("/timeseries/time_s");
    const auto tb = hb.doubles("/timeseries/time_s");
    ASSERT_LT(ta.size(), 5u);  // sparse: the start and the end only
    ASSERT_GT(tb.size(), 100u);
    EXPECT_EQ(ta.back(), tb.back());
    for (const char* field : {"/position", "/velocity"}) {
      const auto xa = ha.doubles(last_frame(ha) + field);
      const auto xb = hb.doubles(last_frame(hb) + field);
      ASSERT_EQ(xa.size(), xb.size()) << field;
      ASSERT_FALSE(xa.empty()) << field;
      for (std::size_t i = 0; i < xa.size(); ++i) ASSERT_EQ(xa[i], xb[i]) << field << " " << i;
    }
    EXPECT_EQ(ha.doubles("/timeseries/tool_force_x_n_per_m").back(),
              hb.doubles("/timeseries/tool_force_x_n_per_m").back());
  }
}

TEST(SaturatedCutting, TakingTurnsChangesNoBitAndTheWallIsSplitByPhase) {
  // coupling.overlap "off": the DEM computes its forces before answering its kinematics instead
  // of while the fluid steps. The same arithmetic in the same order: the same bits.
  const std::vector<std::string> cut = {"--set", "time.end_time_s=0.003", "--set",
                                        "output.frame_interval_s=0.003"};
  std::vector<std::string> on = cut, off = cut;
  on.insert(on.end(), {"--set", "coupling.overlap=on"});
  off.insert(off.end(), {"--set", "coupling.overlap=off"});
  const CouplerRun a = run_small_cut("overlap_on", on);
  const CouplerRun b = run_small_cut("overlap_off", off);
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NE(a.err.find("overlap    the DEM's forces overlap the fluid's step (coupling.overlap "
                       "\"on\""),
            std::string::npos)
      << a.err;
  EXPECT_NE(b.err.find("take turns (coupling.overlap \"off\""), std::string::npos) << b.err;
  EXPECT_NE(a.out_text.find("time       dem busy"), std::string::npos) << a.out_text;
  const H5Reader ha(a.out / "run.h5"), hb(b.out / "run.h5");
  for (const std::string& name : ha.members("/timeseries")) {
    if (name == "step") continue;
    EXPECT_TRUE(bit_identical(ha.doubles("/timeseries/" + name), hb.doubles("/timeseries/" + name)))
        << name;
  }
  EXPECT_TRUE(bit_identical(ha.doubles(last_frame(ha) + "/position"),
                            hb.doubles(last_frame(hb) + "/position")));

  // Where the wall went: each phase non-negative, the phases within the module's busy time, the
  // DEM's work after its replies gone when it takes turns.
  for (const CouplerRun* r : {&a, &b}) {
    const Summary s = coupler::read_summary(r->out / "summary.json");
    for (const std::string who : {"dem", "fluid"}) {
      double phases = 0.0;
      const std::vector<std::string> names =
          who == "dem" ? std::vector<std::string>{"drift", "neighbours", "bonds", "contacts",
                                                  "walls", "barrier", "finish", "breaks"}
                       : std::vector<std::string>{"staleness", "geometry", "boundary", "passes",
                                                  "advance", "force"};
      for (const std::string& n : names) {
        const double v = number(s, who + "_phase_" + n + "_s");
        EXPECT_GE(v, 0.0) << who << " " << n;
        phases += v;
      }
      EXPECT_GT(phases, 0.0) << who;
      EXPECT_LE(phases, number(s, who + "_busy_s") * (1 + 1e-9)) << who;
      EXPECT_GE(number(s, who + "_service_s"), 0.0) << who;
      EXPECT_GE(number(s, who + "_request_s"), 0.0) << who;
    }
    EXPECT_GE(number(s, "coupler_own_s"), 0.0);
    EXPECT_LE(number(s, "coupler_own_s"), number(s, "wall_time_s"));

    // The rebuild counts: the time series' last values (the modules' own counters), the DEM's
    // lists rebuilt as the tool moves, the fluid's geometry built at least once (this 3 ms cut
    // moves nothing far enough for a refresh), and no more rows than full refreshes would take.
    const H5Reader h(r->out / "run.h5");
    const double lists = number(s, "dem_neighbour_rebuilds");
    const double refreshes = number(s, "fluid_geometry_updates");
    EXPECT_EQ(lists, h.doubles("/timeseries/neighbour_rebuilds").back());
    EXPECT_EQ(refreshes, h.doubles("/timeseries/fluid_geometry_updates").back());
    EXPECT_EQ(number(s, "fluid_geometry_local_updates"),
              h.doubles("/timeseries/fluid_geometry_local_updates").back());
    EXPECT_GT(lists, 1.0);
    EXPECT_GE(refreshes, 1.0);
    EXPECT_LE(number(s, "fluid_geometry_local_updates"), refreshes);
    EXPECT_LE(number(s, "fluid_geometry_rows_recomputed"), refreshes * number(s, "particles"));
    EXPECT_GE(number(s, "fluid_geometry_rows_recomputed"), 0.0);
    EXPECT_NE(r->out_text.find("rebuilds   DEM neighbour lists "), std::string::npos) << r->out_text;
  }
  EXPECT_GT(number(coupler::read_summary(a.out / "summary.json"), "dem_after_reply_s"), 0.0);
  // Taking turns, after_reply has nothing to compute: what remains is the timing of an empty
  // call per exchange (with room for a loaded machine's preemptions).
  EXPECT_LT(number(coupler::read_summary(b.out / "summary.json"), "dem_after_reply_s"),
            0.5 * number(coupler::read_summary(a.out / "summary.json"), "dem_after_reply_s"));
}

}  // namespace
}  // namespace rockcut::test
