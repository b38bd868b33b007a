// The Wendland C2 kernel (eq. 18 with the 7 / (pi h^2) normalisation) and the neighbour lists.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <omp.h>

#include "fluid/sp_test_support.hpp"
#include "sp/kernel.hpp"
#include "sp/neighbours.hpp"

namespace rockcut::fluid::test {
namespace {

TEST(Kernel, IntegratesToOneOverThePlane) {
  // Midpoint rule in r on [0, h]: the integrand 2 pi r W(r) is a polynomial of degree 6, so the
  // rule's error is O((h / n)^2); with 20,000 intervals it is ~1e-9.
  const double h = 0.0015;
  const sp::WendlandC2 k(h);
  const int n = 20000;
  double integral = 0.0;
  for (int i = 0; i < n; ++i) {
    const double r = (i + 0.5) * h / n;
    integral += 2.0 * std::numbers::pi * r * k.w(r) * h / n;
  }
  EXPECT_NEAR(integral, 1.0, 1e-8);
  EXPECT_DOUBLE_EQ(k.w(0.0), 7.0 / (std::numbers::pi * h * h));
  EXPECT_EQ(k.w(h), 0.0);
  EXPECT_EQ(k.f(h), 0.0);
  EXPECT_EQ(k.w(1.1 * h), 0.0);
}

TEST(Kernel, FIsTheDerivativeOverR) {
  // Central differences of W: relative error ~ (dr / (h - r))^2 because W' ~ (1 - R)^3 near the
  // edge of the support: 4e-6 at R = 0.95 with dr = 1e-4 h; tolerance 1e-5.
  const double h = 0.002;
  const sp::WendlandC2 k(h);
  for (double R : {0.05, 0.2, 0.5, 0.8, 0.95}) {
    const double r = R * h, dr = 1e-4 * h;
    const double dwdr = (k.w(r + dr) - k.w(r - dr)) / (2 * dr);
    EXPECT_NEAR(k.f(r), dwdr / r, 1e-5 * std::abs(dwdr / r)) << "R = " << R;
    double w, f;
    k.w_and_f(r, w, f);
    EXPECT_DOUBLE_EQ(w, k.w(r));
    EXPECT_DOUBLE_EQ(f, k.f(r));
  }
  EXPECT_LT(k.f(0.0), 0.0);  // finite at r = 0: coincident particles need no special case
  EXPECT_TRUE(std::isfinite(k.f(0.0)));
}

TEST(NeighbourList, MatchesBruteForceSortedAndSymmetric) {
  // On one thread and on three (the rows are shared out, each written at its counted offset).
  for (int threads : {1, 3}) {
  omp_set_num_threads(threads);
  const Particles p = random_packing();
  sp::NeighbourList list(0.0015, 0.1);
  list.build(p.position);
  omp_set_num_threads(1);
  const double rc = 0.0015 * 1.1;
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::vector<int> expected;
    for (std::size_t j = 0; j < p.size(); ++j) {
      if (j != i && std::hypot(p.x(j) - p.x(i), p.y(j) - p.y(i)) < rc) expected.push_back(int(j));
    }
    const auto& nb = list.neighbours();
    const std::vector<int> row(nb.begin() + list.offsets()[i], nb.begin() + list.offsets()[i + 1]);
    ASSERT_EQ(row, expected) << "particle " << i;  // brute force is in index order: sorted
    pairs += expected.size();
  }
  EXPECT_EQ(list.pairs(), pairs) << threads << " threads";
  EXPECT_EQ(pairs % 2, 0u);
  }
}

TEST(NeighbourList, RebuildsOnlyWhenAParticleMovedMoreThanHalfTheSkin) {
  Particles p = jittered(20, 20, 0.0006, 0.3, 3);
  sp::NeighbourList list(0.0015, 0.1);  // skin 0.15 mm: rebuild beyond 0.075 mm
  EXPECT_TRUE(list.update(p.position));
  EXPECT_EQ(list.builds(), 1u);
  p.position[10] += 0.7e-4;
  EXPECT_FALSE(list.update(p.position));
  p.position[10] += 0.1e-4;  // 0.8e-4 m from where it was at the build
  EXPECT_TRUE(list.update(p.position));
  EXPECT_EQ(list.builds(), 2u);
  // Without a skin any motion rebuilds.
  sp::NeighbourList tight(0.0015, 0.0);
  tight.update(p.position);
  EXPECT_FALSE(tight.update(p.position));
  p.position[3] += 1e-12;
  EXPECT_TRUE(tight.update(p.position));
}

TEST(NeighbourList, FarApartParticlesDoNotBlowUpTheGrid) {
  // Two clusters a kilometre apart: the cell grid is widened instead of holding 1e12 cells.
  Particles p = lattice(5, 5, 0.0006, 0.0002);
  p.position.insert(p.position.end(), {1000.0, 1000.0});
  p.radius.push_back(0.0002);
  sp::NeighbourList list(0.0015, 0.1);
  list.build(p.position);
  EXPECT_EQ(list.offsets()[26] - list.offsets()[25], 0);
  EXPECT_GT(list.pairs(), 0u);
}

}  // namespace
}  // namespace rockcut::fluid::test
