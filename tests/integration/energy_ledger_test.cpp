// The energy ledger (DESIGN section 5) through a break cascade: a bonded hexagonal lattice crushed
// in the UCS test, its bonds weak enough that most of them break, many in shear while their discs
// are pressed together (the contact then takes the normal load over).
#include <gtest/gtest.h>

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

struct Crushed {
  double imbalance_rel = 0.0;
  int tensile = 0, shear = 0;
};

// local: the paper's eq. 10; else dashpots (zeta 0.1) with rolling springs (mu_r 0.1).
Crushed crush_lattice(const std::string& name, bool clamp, bool local = true) {
  const fs::path dir = fresh_dir(name);
  const fs::path scene = dir / (name + ".pbtxt");
  // 20 x 24 discs of 1 mm, the printed-swapped stiffnesses, strengths of 1e4 N/m: the first bonds
  // break at 0.74 ms, and by 2 ms about 1,250 of the 1,353 bonds have broken (460 in tension, 790
  // in shear, nearly all of those under compression).
  std::ofstream(scene)
      << "title: \"hexagonal lattice crushed\"\n"
         "time { end_time_s: 0.002 }\n"
         "output { timeseries_every_steps: 1000 frame_interval_s: 0 }\n"
         "dem {\n"
         "  lattice { nx: 20 ny: 24 spacing_m: 0.001 radius_m: 0.0005 arrangement: \"hexagonal\" }\n"
         "  contact { normal_stiffness_pa: 2.5e10 shear_stiffness_pa: 1e10 friction: 1 "
      << (local ? "" : "rolling_friction: 0.1 ") << "}\n"
         "  bonds { normal_stiffness_pa: 2.5e10 shear_stiffness_pa: 1e10\n"
         "          tensile_strength_n_per_m: 1e4 shear_strength_n_per_m: 1e4 }\n"
      << (local ? "  damping { local_coefficient: 0.7 }\n"
                : "  damping { model: \"viscous\" damping_ratio: 0.1 }\n")
      << "  loading_test { kind: \"ucs\" platen_speed_m_s: 0.02 platen_friction: 0 clamp_end_layers: "
      << (clamp ? "true" : "false") << " }\n}\n";
  const CouplerRun r = run_coupler(scene.string(), {}, dir, std::chrono::milliseconds(60000));
  EXPECT_EQ(r.code, 0) << r.err;
  Crushed c;
  c.imbalance_rel = number(coupler::read_summary(r.out / "summary.json"), "energy_imbalance_rel");
  for (double mode : H5Reader(r.out / "run.h5").doubles("/breaks/mode")) {
    (mode == 0.0 ? c.tensile : c.shear) += 1;
  }
  return c;
}

// Measured imbalance: 0.17 % with clamped ends and 0.19 % without (before the freed pair's contact
// acted in the evaluation of the break: 1.9 % and 1.5 %; in the 40 x 46 lattice of the issue 2.6 %
// and 1.1 %). The rest is the trapezoid rule's error over the violent steps of the cascade. 0.5 %
// is the bound asked of the ledger; the break counts show that the cascade happened.
TEST(EnergyLedger, ClosesThroughTheBreakCascadeOfACrushedHexagonalLattice) {
  for (bool clamp : {true, false}) {
    const Crushed c = crush_lattice(clamp ? "ledger_hex_clamped" : "ledger_hex_free", clamp);
    EXPECT_GT(c.shear, 300) << "clamp " << clamp;
    EXPECT_GT(c.tensile, 100) << "clamp " << clamp;
    EXPECT_LT(std::abs(c.imbalance_rel), 0.005) << "clamp " << clamp;
  }
}

}  // namespace
}  // namespace rockcut::test

namespace rockcut::test {
namespace {

// The same cascade under dashpots and rolling springs: what they dissipate is booked
// (viscous_damping_j, rolling_j), and the ledger closes to the same 0.5 %.
TEST(EnergyLedger, ClosesUnderDashpotsAndRollingSprings) {
  const Crushed c = crush_lattice("ledger_hex_viscous", false, /*local=*/false);
  EXPECT_GT(c.shear + c.tensile, 400);
  EXPECT_LT(std::abs(c.imbalance_rel), 0.005);
}

}  // namespace
}  // namespace rockcut::test
