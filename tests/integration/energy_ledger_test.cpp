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

enum class Damping { local, dashpots_and_rolling, none };

// local: the paper's eq. 10; dashpots (zeta 0.1) with rolling springs (mu_r 0.1); or none.
Crushed crush_lattice(const std::string& name, bool clamp, Damping damping = Damping::local,
                      double softening_ratio = 0.0) {
  const bool local = damping == Damping::local, rolling = damping == Damping::dashpots_and_rolling;
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
      << (rolling ? "rolling_friction: 0.1 " : "") << "}\n"
         "  bonds { normal_stiffness_pa: 2.5e10 shear_stiffness_pa: 1e10\n"
         "          tensile_strength_n_per_m: 1e4 shear_strength_n_per_m: 1e4 softening_ratio: "
      << softening_ratio << " }\n"
      << (local     ? "  damping { local_coefficient: 0.7 }\n"
          : rolling ? "  damping { model: \"viscous\" damping_ratio: 0.1 }\n"
                    : "  damping { model: \"none\" }\n")
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

// Measured imbalance: 0.0016 % with clamped ends and 0.0010 % without. With friction booked as the
// limit times the slip and a broken bond as its energy at the break (rather than as the kick left
// them, core/contact_law.hpp and core/bond_law.hpp) it was 0.17 % and 0.19 %; before the freed
// pair's contact acted in the evaluation of the break, 1.9 % and 1.5 %. What remains is Verlet's
// own error where contacts open and close within a step. The bound, 0.05 %, is a tenth of the
// 0.5 % asked of the ledger and thirty times the measured; the break counts show that the
// cascade happened.
TEST(EnergyLedger, ClosesThroughTheBreakCascadeOfACrushedHexagonalLattice) {
  for (bool clamp : {true, false}) {
    const Crushed c = crush_lattice(clamp ? "ledger_hex_clamped" : "ledger_hex_free", clamp);
    EXPECT_GT(c.shear, 300) << "clamp " << clamp;
    EXPECT_GT(c.tensile, 100) << "clamp " << clamp;
    EXPECT_LT(std::abs(c.imbalance_rel), 5e-4) << "clamp " << clamp;
  }
}

}  // namespace
}  // namespace rockcut::test

namespace rockcut::test {
namespace {

// The same cascade under dashpots and rolling springs, and with no damping at all: what they
// dissipate is booked (viscous_damping_j, rolling_j; friction takes what the dashpots would).
// Measured 0.0125 % and 0.080 %. With the dashpots booked as c v^2 dt, friction as the limit
// times the slip and a break as the bond's energy at it, the first closed to 0.42 %, and the
// undamped lattice with rolling springs to 1.5 % (0.041 % now). Undamped, the discs keep
// meeting and parting, each time with Verlet's error: its bound is 0.2 %, the damped one's 0.05 %.
TEST(EnergyLedger, ClosesUnderDashpotsAndRollingSpringsAndWithoutDamping) {
  for (Damping damping : {Damping::dashpots_and_rolling, Damping::none}) {
    const bool none = damping == Damping::none;
    const Crushed c =
        crush_lattice(none ? "ledger_hex_undamped" : "ledger_hex_viscous", false, damping);
    EXPECT_GT(c.shear + c.tensile, 400) << "none " << none;
    EXPECT_LT(std::abs(c.imbalance_rel), none ? 2e-3 : 5e-4) << "none " << none;
  }
}

}  // namespace
}  // namespace rockcut::test

namespace rockcut::test {
namespace {

// Softening bonds (dem.bonds.softening_ratio 3, core/bond_softening.hpp) under dashpots: every
// step of a bond on its way down is booked as the trapezoid less its secant energy's change, and
// the cascade's ledger closes as the brittle one's does.
TEST(EnergyLedger, ClosesThroughTheCascadeOfSofteningBonds) {
  const Crushed c =
      crush_lattice("ledger_hex_softening", false, Damping::dashpots_and_rolling, 3.0);
  EXPECT_GT(c.shear + c.tensile, 100);
  EXPECT_LT(std::abs(c.imbalance_rel), 5e-4);
}

}  // namespace
}  // namespace rockcut::test
