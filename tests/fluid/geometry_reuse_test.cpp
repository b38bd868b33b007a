// Reusing the SP geometry between fluid steps (fluid.geometry_refresh_distance): the operators of a
// configuration applied to fields of a configuration moved by up to delta. Their error must grow
// linearly in delta / h, with the constant the scene reference quotes, and the model must
// recompute the geometry as soon as anything has moved further than the distance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "fluid/sp_test_support.hpp"
#include "sp/operators.hpp"

namespace rockcut::fluid::test {
namespace {

constexpr double kH = 0.0015;  // [m], Table 1

// Every centre moved by a random vector of length up to delta_m (seeded): disordered motion, the
// case the reuse is worst at (a rigid motion changes no operator, a uniform strain only by the
// strain itself).
Particles moved(const Particles& p, double delta_m, std::uint64_t seed) {
  Particles q = p;
  std::mt19937_64 rng(seed);
  auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };  // [0, 1)
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = delta_m * uniform(), a = 2.0 * M_PI * uniform();
    q.position[2 * i] += r * std::cos(a);
    q.position[2 * i + 1] += r * std::sin(a);
  }
  return q;
}

struct Errors {
  double gradient_rms = 0, gradient_max = 0, divergence_rms = 0;
};

// The stale operators (geometry of `at`) on linear fields sampled at the moved centres, against
// the exact gradient and divergence. The fresh operators are exact for these fields to 1e-10
// (cspm_test.cpp), so this is the reuse error alone. Fully corrected particles only.
Errors stale_errors(const Initialised& at, const Particles& now) {
  const double cx = 3e6, cy = -7e6;          // grad p [Pa/m]
  const double exx = 2.0, exy = 0.5, eyy = -1.0;  // grad u [1/s]: div u = 1
  const std::size_t n = now.size();
  std::vector<double> p(n), u(2 * n), grad(2 * n), div(n);
  for (std::size_t i = 0; i < n; ++i) {
    p[i] = cx * now.x(i) + cy * now.y(i);
    u[2 * i] = exx * now.x(i) + exy * now.y(i);
    u[2 * i + 1] = exy * now.x(i) + eyy * now.y(i);
  }
  sp::gradient(at.geo(), p, grad);
  sp::divergence(at.geo(), u, div);
  Errors e;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (at.geo().correction[i] != sp::Correction::full) continue;
    const double g = std::hypot(grad[2 * i] - cx, grad[2 * i + 1] - cy) / std::hypot(cx, cy);
    const double d = std::abs(div[i] - (exx + eyy)) / std::hypot(std::hypot(exx, eyy), exy);
    e.gradient_rms += g * g;
    e.gradient_max = std::max(e.gradient_max, g);
    e.divergence_rms += d * d;
    ++count;
  }
  e.gradient_rms = std::sqrt(e.gradient_rms / count);
  e.divergence_rms = std::sqrt(e.divergence_rms / count);
  return e;
}

TEST(GeometryReuse, OperatorErrorIsLinearInTheMotionSinceTheGeometry) {
  const Initialised at(random_packing(), kH);
  std::vector<Errors> errors;
  const std::vector<double> fractions = {0.001, 0.002, 0.004, 0.01, 0.02};
  for (double f : fractions) {
    errors.push_back(stale_errors(at, moved(at.particles, f * kH, 11)));
    const Errors& e = errors.back();
    std::printf("delta / h = %.3f: gradient rms %.2e max %.2e, divergence rms %.2e\n", f,
                e.gradient_rms, e.gradient_max, e.divergence_rms);
  }
  for (std::size_t k = 0; k < fractions.size(); ++k) {
    const double f = fractions[k];
    // The scene reference quotes an rms error of about 0.7 times delta / h and a largest of
    // about 4 times (measured 0.66 / 0.48 and 3.7): bounds 1 and 5 leave 35-50 % for another
    // packing or seed, and fail if the error were of order (delta / h)^(1/2) or sqrt(delta/d).
    EXPECT_LT(errors[k].gradient_rms, 1.0 * f);
    EXPECT_LT(errors[k].divergence_rms, 1.0 * f);
    EXPECT_LT(errors[k].gradient_max, 5.0 * f);
    // First order: the error grows as delta, up to twice the default distance (0.02). Within a
    // tenth of the ratio of the distances: the random lengths scale exactly,
    // and second-order terms are delta / h <= 2e-2 of them.
    if (k > 0) {
      const double ratio = f / fractions[k - 1];
      EXPECT_NEAR(errors[k].gradient_rms / errors[k - 1].gradient_rms, ratio, 0.1 * ratio);
      EXPECT_NEAR(errors[k].divergence_rms / errors[k - 1].divergence_rms, ratio, 0.1 * ratio);
    }
  }
}

TEST(GeometryReuse, GeometryIsRecomputedOnceAnythingHasMovedFurtherThanTheDistance) {
  // A uniform strain rate exx about the origin moves the outermost centre (|x| <= 15 mm) by
  // exx dt |x| per step: 1.5e-7 m at exx = 10 /s and dt = 1 us. With the distance 0.0105 h =
  // 1.575e-5 m the geometry is stale after 105 steps: 250 steps recompute it twice.
  for (double refresh : {0.0105, 0.0}) {
    sp::SpParams params = table1(kH);
    params.geometry_refresh = refresh;
    params.dynamic_solid = false;
    sp::ExplicitModel model(params);
    Driver driver(model, random_packing());  // initialises, then the t = 0 exchange
    for (int k = 0; k < 250; ++k) driver.step(1e-6, 10.0, 0.0);
    // Without reuse every exchange recomputes, the t = 0 one included.
    EXPECT_EQ(model.geometry_updates(), refresh > 0 ? 2u : 251u) << "refresh " << refresh;
  }
}

TEST(GeometryReuse, AMovingWallAloneRecomputesOnlyTheBoundary) {
  // A tool segment above the packing's top surface moves down 0.1 mm (0.067 h) per step onto
  // it while the particles stay still. The kernel sums do not see walls, so the geometry is
  // computed once (the t = 0 exchange) and only the boundary follows the tool, giving every step
  // the boundary of a model that recomputes everything (refresh 0), bit for bit.
  const Particles p = random_packing();
  double top = -1.0;
  for (std::size_t i = 0; i < p.size(); ++i) top = std::max(top, p.y(i));
  auto make = [&](double refresh) {
    sp::SpParams params = table1(kH);
    params.geometry_refresh = refresh;
    params.dynamic_solid = false;
    auto model = std::make_unique<sp::ExplicitModel>(params);
    model->initialise({p.radius, p.position});
    return model;
  };
  const auto reused = make(0.002), fresh = make(0.0);
  const std::vector<double> zero(2 * p.size(), 0.0);
  std::vector<double> force(2 * p.size());
  std::size_t sealed_before = 0, sealed_after = 0;
  for (int k = 0; k <= 25; ++k) {
    const double y = top + 2e-3 - 1e-4 * k;  // from 2 mm above the top centres to 0.5 mm below
    const std::vector<double> tool = {-5e-3, y, 5e-3, y};
    const Kinematics kin{p.position, zero, zero, tool};
    const double dt = k == 0 ? 0.0 : 1e-6;
    reused->step(dt, k * 1e-6, kin, force);
    fresh->step(dt, k * 1e-6, kin, force);
    const auto a = reused->boundary(), b = fresh->boundary();
    ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "step " << k;
    const auto sealed = static_cast<std::size_t>(std::count(a.begin(), a.end(), sp::Boundary::sealed));
    (k == 0 ? sealed_before : sealed_after) = sealed;
  }
  EXPECT_EQ(reused->geometry_updates(), 1u);
  EXPECT_EQ(reused->boundary_updates(), 25u);
  EXPECT_EQ(fresh->geometry_updates(), 26u);
  EXPECT_GT(sealed_after, sealed_before);  // the tool reached the surface and seals it
}

}  // namespace
}  // namespace rockcut::fluid::test
