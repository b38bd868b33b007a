// The cell grid with positions a blown-up run can hold (NaN, infinite, 1e300): it bins them at an
// edge instead of overflowing an int (undefined behaviour that UBSan reported), and still finds
// the near pairs of the finite ones.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "core/cell_grid.hpp"

namespace rockcut::dem {
namespace {

TEST(CellGrid, NonFiniteAndFarPositionsAreBinnedAtAnEdge) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> position = {0.0, 0.0,  0.001, 0.0,  nan, 0.0,   0.0, inf,
                                        1e300, -1e300, 0.0, 0.001, -inf, nan};
  CellGrid grid;
  grid.build(position, 0.002);
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  grid.for_each_near_pair([&](std::uint32_t i, std::uint32_t j) { pairs.insert({i, j}); });
  // The three finite discs near the origin are each other's neighbours.
  EXPECT_TRUE(pairs.count({0, 1}));
  EXPECT_TRUE(pairs.count({0, 5}));
  EXPECT_TRUE(pairs.count({1, 5}));
}

}  // namespace
}  // namespace rockcut::dem
