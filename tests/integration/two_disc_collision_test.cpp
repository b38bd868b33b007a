// Head-on two-disc collisions end to end (cases/verification/two_disc_collision*.pbtxt): the discs'
// velocities come from the packing file (`x y r vx vy [omega]`), the contact law of DESIGN section
// 4 acts, and the run's time series and last frame give the contact time and the restitution.
// Closed forms:
//   without damping: t_c = pi sqrt(m_eff / k_n), e = 1;
//   with local damping alpha (per disc), discs moving towards their centre of mass: each feels
//   (1 + alpha) F approaching and (1 - alpha) F separating, so t_c = pi/2 sqrt(m_eff / k_n)
//   (1 / sqrt(1 + alpha) + 1 / sqrt(1 - alpha)) and e = sqrt((1 - alpha) / (1 + alpha));
//   with dashpots of damping ratio zeta (the linear spring-dashpot, core/viscous_damping.hpp):
//   t_c = pi sqrt(m_eff / k_n) / sqrt(1 - zeta^2) and e = exp(-pi zeta / sqrt(1 - zeta^2)),
//   whatever frame the discs move in (the dashpot sees relative velocity only).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "integration/h5_read.hpp"
#include "integration/process_helpers.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;

struct Case {
  const char* name;
  const char* scene;
  double alpha;  ///< local damping
  double zeta;   ///< the dashpots' damping ratio
  std::vector<std::string> sets;
};

// Measured (the four undamped and locally damped cases): contact time within 0.03 % and
// restitution within 1e-5 of the closed form; the two dashpot cases pass the same 0.2 %.
// The contact is sampled every step, 2,000 steps per contact (0.05 % resolution), and velocity
// Verlet's phase error at that step is ~1e-6; the damping switches sign within one step of the
// largest compression. 0.2 % on both separates the damped from the undamped answers (10 % apart
// in e, 0.4 % in t_c) and catches a wrong mass or stiffness (a factor 2 moves t_c by 41 %).
TEST(TwoDiscCollision, ContactTimeAndRestitutionMatchTheClosedForms) {
  const double zeta_of_e_half = -std::log(0.5) / std::hypot(std::numbers::pi, std::log(0.5));
  const std::vector<Case> cases = {
      {"equal", "two_disc_collision.pbtxt", 0.0, 0.0, {}},
      {"equal_damped",
       "two_disc_collision.pbtxt",
       0.1,
       0.0,
       {"--set", "dem.damping.model=local", "--set", "dem.damping.local_coefficient=0.1"}},
      {"mass_4to1", "two_disc_collision_4to1.pbtxt", 0.0, 0.0, {}},
      {"mass_4to1_damped",
       "two_disc_collision_4to1.pbtxt",
       0.1,
       0.0,
       {"--set", "dem.damping.model=local", "--set", "dem.damping.local_coefficient=0.1", "--set",
        "dem.initial_velocity_m_s.x=-0.02"}},
      {"equal_dashpots",
       "two_disc_collision.pbtxt",
       0.0,
       0.1,
       {"--set", "dem.damping.model=viscous", "--set", "dem.damping.damping_ratio=0.1"}},
      // Given by its restitution, in a moving frame: 4:1 masses, e = 0.5 (zeta 0.2155).
      {"mass_4to1_restitution",
       "two_disc_collision_4to1.pbtxt",
       0.0,
       zeta_of_e_half,
       {"--set", "dem.damping.model=viscous", "--set", "dem.damping.restitution=0.5", "--set",
        "dem.initial_velocity_m_s.x=0.013"}},
  };
  const double k = 1e8, dt = 1e-8;  // the scenes' contact normal stiffness and step
  for (const Case& c : cases) {
    const fs::path dir = fresh_dir(std::string("two_disc_") + c.name);
    const CouplerRun r = run_coupler(source(std::string("cases/verification/") + c.scene), c.sets,
                                     dir, std::chrono::milliseconds(60000));
    ASSERT_EQ(r.code, 0) << c.name << "\n" << r.err;
    const H5Reader h5(r.out / "run.h5");
    const std::vector<double> v0 = h5.doubles("/frames/000000/velocity");
    const std::string last = last_frame(h5);
    const std::vector<double> v1 = h5.doubles(last + "/velocity");
    const std::vector<double> radius = h5.doubles(last + "/radius");
    const std::vector<double> x = h5.doubles(last + "/position");
    ASSERT_EQ(v0.size(), 4u);
    // Disc a is the left one.
    const int a = x[0] < x[2] ? 0 : 1, b = 1 - a;
    const double m_a = 2800 * std::numbers::pi * radius[a] * radius[a];
    const double m_b = 2800 * std::numbers::pi * radius[b] * radius[b];
    const double m_eff = m_a * m_b / (m_a + m_b);
    const double t_c = 0.5 * std::numbers::pi * std::sqrt(m_eff / k) *
                       (1.0 / std::sqrt(1.0 + c.alpha) + 1.0 / std::sqrt(1.0 - c.alpha)) /
                       std::sqrt(1.0 - c.zeta * c.zeta);
    const double e_exact = std::sqrt((1.0 - c.alpha) / (1.0 + c.alpha)) *
                           std::exp(-std::numbers::pi * c.zeta / std::sqrt(1.0 - c.zeta * c.zeta));
    const double e = (v1[2 * b] - v1[2 * a]) / (v0[2 * a] - v0[2 * b]);
    int touching = 0;
    for (double s : h5.doubles("/timeseries/strain_energy_j")) touching += s > 0.0;
    EXPECT_GT(v0[2 * a], v0[2 * b]) << c.name << ": the file's velocities were not applied";
    EXPECT_NEAR(touching * dt / t_c, 1.0, 2e-3) << c.name;
    EXPECT_NEAR(e / e_exact, 1.0, 2e-3) << c.name;
    // Momentum: the contact forces, and the damping forces (|F| is the same on both discs, their
    // velocities of opposite signs in the damped cases' frames), are equal and opposite.
    EXPECT_NEAR(m_a * v1[2 * a] + m_b * v1[2 * b], m_a * v0[2 * a] + m_b * v0[2 * b],
                1e-9 * m_a * std::abs(v0[2 * a]))
        << c.name;
  }
}

}  // namespace
}  // namespace rockcut::test
