// The local geometry refresh (sp::refresh_geometry, docs/model.md "Reusing the geometry"):
// moving only the particles that moved and recomputing the rings of rows that depend on them must
// give, bit for bit, the geometry and step coefficients that a full update computes on the same
// configuration X'. Exact equality is the right tolerance: every row is computed alone by the same
// code in the same order, so any difference is a row the rings missed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include "fluid/sp_test_support.hpp"
#include "sp/geometry.hpp"
#include "sp/step_operator.hpp"

namespace rockcut::fluid::test {
namespace {

constexpr double kH = 0.0015;  // [m], Table 1

// Bitwise equality of two doubles (EXPECT_EQ would pass -0 == +0 and fail NaN == NaN).
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// How many values of the two geometries differ in their bits: per particle, and per kept pair
// (the slots past row_end are scratch and not compared).
std::size_t differences(const sp::Geometry& a, const sp::Geometry& b) {
  std::size_t count = 0;
  auto compare = [&](const std::vector<double>& x, const std::vector<double>& y) {
    EXPECT_EQ(x.size(), y.size());
    for (std::size_t k = 0; k < std::min(x.size(), y.size()); ++k) count += !same_bits(x[k], y[k]);
  };
  compare(a.position, b.position);
  compare(a.volume, b.volume);
  compare(a.volume_iterates, b.volume_iterates);
  compare(a.l_inverse, b.l_inverse);
  compare(a.div_r, b.div_r);
  compare(a.l_trace, b.l_trace);
  compare(a.normal, b.normal);
  for (std::size_t i = 0; i < a.particles(); ++i) {
    count += a.correction[i] != b.correction[i];
    if (a.row_end[i] != b.row_end[i]) {
      ++count;
      continue;
    }
    for (int k = a.row_begin[i]; k < a.row_end[i]; ++k) {
      const auto s = static_cast<std::size_t>(k);
      count += a.neighbours[s] != b.neighbours[s];
      count += !same_bits(a.w[s], b.w[s]) + !same_bits(a.f[s], b.f[s]);
    }
  }
  return count;
}

// The step's divergence, Laplacian and force of two operators on the same random fields: how
// many of the values differ in their bits.
std::size_t step_differences(const sp::StepOperator& a, const sp::Geometry& geo_a,
                             const sp::StepOperator& b, const sp::Geometry& geo_b) {
  const std::size_t n = geo_a.particles();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> vel(2 * n), p(n), g(n);
  for (double& x : vel) x = u(rng);
  for (double& x : p) x = 1e5 * u(rng);
  for (double& x : g) x = 1e-3 * u(rng);
  std::vector<double> div_a(n), lap_a(n), force_a(2 * n), div_b(n), lap_b(n), force_b(2 * n);
  a.divergence_laplacian(geo_a, vel, p, div_a, lap_a);
  b.divergence_laplacian(geo_b, vel, p, div_b, lap_b);
  a.adjoint_force(geo_a, g, force_a);
  b.adjoint_force(geo_b, g, force_b);
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    count += !same_bits(div_a[i], div_b[i]) + !same_bits(lap_a[i], lap_b[i]);
    count += !same_bits(force_a[2 * i], force_b[2 * i]);
    count += !same_bits(force_a[2 * i + 1], force_b[2 * i + 1]);
  }
  return count;
}

class LocalRefresh : public ::testing::TestWithParam<unsigned> {};

TEST_P(LocalRefresh, EqualsAFullUpdateOnTheSameConfigurationBitForBit) {
  const unsigned iterations = GetParam();
  const Particles p = random_packing();
  const std::size_t n = p.size();
  const Initialised init(p, kH);  // for its neighbour list (skin 0.1 h)
  const sp::NeighbourList& list = init.list();
  const sp::WendlandC2 kernel(kH);
  std::vector<double> lucy(n);
  for (std::size_t i = 0; i < n; ++i) lucy[i] = std::numbers::pi * p.radius[i] * p.radius[i] / 0.85;

  sp::Geometry local, full;
  sp::update_geometry(list, kernel, p.position, lucy, iterations, local);
  sp::StepOperator local_op, full_op;
  local_op.build(local);
  sp::LocalRefresh scratch;

  // Three refreshes, each moving the particles within 2.5 mm of a different centre by random
  // vectors of up to 0.02 h (the list stays valid: no particle moves half its 0.1 h skin, 0.05 h,
  // in all three).
  std::vector<double> x = p.position;
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double centres[3][2] = {{-4e-3, 2e-3}, {6e-3, -5e-3}, {-4.5e-3, 1e-3}};
  for (const auto& c : centres) {
    std::vector<int> moved;
    for (std::size_t i = 0; i < n; ++i) {
      if (std::hypot(x[2 * i] - c[0], x[2 * i + 1] - c[1]) > 2.5e-3) continue;
      x[2 * i] += 0.014 * kH * u(rng);
      x[2 * i + 1] += 0.014 * kH * u(rng);
      moved.push_back(static_cast<int>(i));
    }
    ASSERT_GT(moved.size(), 50u);
    ASSERT_TRUE(sp::refresh_geometry(list, kernel, x, moved, lucy, iterations, 1.0, scratch, local));
    // The refresh must be local (else the test would not test the rings): a 2.5 mm patch and
    // iterations + 3 rings of at most 1.1 h = 1.65 mm reach at most ~5-12 mm of the 30 mm window.
    EXPECT_LT(scratch.coefficient_rows.size(), n * 3 / 4);
    EXPECT_GT(scratch.coefficient_rows.size(), 2 * moved.size());
    EXPECT_TRUE(local_op.rebuild_rows(local, scratch.coefficient_rows));

    sp::update_geometry(list, kernel, local.position, lucy, iterations, full);
    full_op.build(full);
    EXPECT_EQ(differences(local, full), 0u) << "iterations " << iterations;
    EXPECT_EQ(step_differences(local_op, local, full_op, full), 0u) << "iterations " << iterations;
    // And it is a new geometry: the moved particles are where they were sent.
    for (int i : moved) EXPECT_TRUE(same_bits(local.position[2 * i], x[2 * i]));
  }
}

INSTANTIATE_TEST_SUITE_P(VolumeIterations, LocalRefresh, ::testing::Values(0u, 1u, 3u));

TEST(LocalRefreshLimit, ARefreshThatWouldNotPayChangesNothing) {
  const Particles p = random_packing();
  const Initialised init(p, kH);
  const sp::WendlandC2 kernel(kH);
  const std::vector<double> lucy(p.size(), 1e-7);
  sp::Geometry geo;
  sp::update_geometry(init.list(), kernel, p.position, lucy, 3, geo);
  const sp::Geometry before = geo;
  std::vector<double> x = p.position;
  for (double& v : x) v += 1e-6;
  const std::vector<int> moved = {0};
  sp::LocalRefresh scratch;
  // One particle's six rings (radius up to 6 x 1.1 h = 10 mm) hold more than 1 % of the 2563.
  EXPECT_FALSE(sp::refresh_geometry(init.list(), kernel, x, moved, lucy, 3, 0.01, scratch, geo));
  EXPECT_EQ(geo.version, before.version);
  EXPECT_EQ(differences(geo, before), 0u);
  EXPECT_TRUE(sp::refresh_geometry(init.list(), kernel, x, moved, lucy, 3, 1.0, scratch, geo));
  EXPECT_EQ(geo.version, before.version + 1);
  // A geometry of other volume iterations does not match: refused, nothing changed.
  sp::Geometry other = before;
  EXPECT_FALSE(sp::refresh_geometry(init.list(), kernel, x, moved, lucy, 2, 0.5, scratch, other));
  EXPECT_EQ(differences(other, before), 0u);
}

TEST(LocalRefreshModel, AModelRefreshesLocallyAndKeepsTheLagBelowTheDistance) {
  // The particles within 3 mm of a point (a patch near the tool) move at 2 m/s, the rest of the
  // packing stays still: the model must refresh locally, every particle must lag its geometry by
  // at most the refresh distance after every step, and the geometry, the boundary and the force
  // must be those of a full update on the model's configuration X', bit for bit.
  const Particles p = random_packing();
  const std::size_t n = p.size();
  sp::SpParams params = table1(kH);
  params.geometry_refresh = 0.002;
  params.dynamic_solid = false;
  sp::ExplicitModel model(params);
  model.initialise({p.radius, p.position});
  std::vector<double> x = p.position, d(2 * n, 0.0), v(2 * n, 0.0), force(2 * n);
  std::vector<bool> patch(n);
  for (std::size_t i = 0; i < n; ++i) patch[i] = std::hypot(x[2 * i] - 3e-3, x[2 * i + 1]) < 3e-3;
  const double dt = 1e-6, limit = params.geometry_refresh * kH;
  model.step(0.0, 0.0, {x, v, d, {}}, force);
  // 30 steps move the patch 60 um, less than half the skin (0.05 h = 75 um): the list stays.
  for (int step = 1; step <= 30; ++step) {
    for (std::size_t i = 0; i < n; ++i) {
      // 2 m/s along a direction that turns with the particle, so the patch also deforms.
      const double a = 0.1 * static_cast<double>(i);
      v[2 * i] = patch[i] ? 2.0 * std::cos(a) : 0.0;
      v[2 * i + 1] = patch[i] ? 2.0 * std::sin(a) : 0.0;
      d[2 * i] = dt * v[2 * i];
      d[2 * i + 1] = dt * v[2 * i + 1];
      x[2 * i] += d[2 * i];
      x[2 * i + 1] += d[2 * i + 1];
    }
    model.step(dt, step * dt, {x, v, d, {}}, force);
    const sp::Geometry& geo = model.geometry();
    double lag = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      lag = std::max(lag, std::hypot(x[2 * i] - geo.position[2 * i],
                                     x[2 * i + 1] - geo.position[2 * i + 1]));
    }
    ASSERT_LE(lag, limit) << "step " << step;
  }
  // 2 um per step against a distance of 3 um: a refresh every second step, all local.
  EXPECT_GE(model.geometry_updates(), 14u);
  EXPECT_EQ(model.local_updates(), model.geometry_updates());

  // A full update on X' (the model's geometry positions) with the model's lists, Lucy volumes
  // (as PorePressureModel::initialise computes them) and box sides.
  const sp::Geometry& geo = model.geometry();
  std::vector<double> lucy(n);
  for (std::size_t i = 0; i < n; ++i) {
    lucy[i] = std::numbers::pi * p.radius[i] * p.radius[i] / model.packing_fraction();
  }
  sp::Geometry full;
  sp::update_geometry(model.neighbour_list(), sp::WendlandC2(kH), geo.position, lucy,
                      params.volume_iterations, full);
  EXPECT_EQ(differences(geo, full), 0u);
  sp::Sides sides;
  sides.fit(p.position);
  sides.sealed = params.sealed;
  std::vector<sp::Boundary> boundary(n);
  sp::classify_boundary(full.div_r, full.normal, params.surface_div_r, kH, full.position, p.radius,
                        sides, boundary);
  std::size_t boundary_differences = 0;
  for (std::size_t i = 0; i < n; ++i) boundary_differences += boundary[i] != model.boundary()[i];
  EXPECT_EQ(boundary_differences, 0u);
  // The last step's force: the full geometry's coefficients on the model's pressure, with the
  // area the model gives the excess pressure (PorePressureModel::update_share).
  sp::StepOperator op;
  op.build(full);
  std::vector<double> g(n), full_force(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    g[i] = model.packing_fraction() * full.volume[i] * (model.pressure()[i] - params.p_hydro_pa);
  }
  op.adjoint_force(full, g, full_force);
  std::size_t force_differences = 0;
  for (std::size_t k = 0; k < 2 * n; ++k) force_differences += !same_bits(force[k], full_force[k]);
  EXPECT_EQ(force_differences, 0u);
  EXPECT_EQ(model.neighbour_list().builds(), 1u);  // the list was never rebuilt
}

}  // namespace
}  // namespace rockcut::fluid::test
