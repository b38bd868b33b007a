// The SP operators as written for speed (sp/operators.hpp and its definitions: rows of the pairs
// inside the support, x and y in one 2-wide vector) against the plain formulas over every pair of the neighbour list,
// skin pairs included, with the kernel evaluated here. The two must agree to the last bit: every
// term the fast code leaves out is an exact zero (W = F = 0 beyond h), and each product and sum
// is taken in the same order. A regression that drops a pair inside the support, mixes x and y,
// or reorders a sum fails here, where the analytical tests would only see a small drift.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "fluid/sp_test_support.hpp"
#include "sp/operators.hpp"

namespace rockcut::fluid::test {
namespace {

// One listed pair's F_ij and W_ij, as update_geometry computes them.
struct PairKernel {
  double w, f;
};

class ReferenceOperators {
 public:
  ReferenceOperators(const sp::NeighbourList& list, const sp::Geometry& geo, double h_m)
      : list_(list), geo_(geo) {
    const sp::WendlandC2 kernel(h_m);
    const auto& off = list.offsets();
    const auto& nb = list.neighbours();
    const double* x = geo.position.data();
    for (std::size_t i = 0; i + 1 < off.size(); ++i) {
      for (int k = off[i]; k < off[i + 1]; ++k) {
        const int j = nb[k];
        const double dx = x[2 * j] - x[2 * i], dy = x[2 * j + 1] - x[2 * i + 1];
        PairKernel p{};
        kernel.w_and_f(std::sqrt(dx * dx + dy * dy), p.w, p.f);
        pairs_.push_back(p);
      }
    }
  }

  // The same sums as sp::divergence_laplacian, scalar, over the whole list.
  void divergence_laplacian(const std::vector<double>& vel, const std::vector<double>& a,
                            std::vector<double>& div, std::vector<double>& lap) const {
    const auto& off = list_.offsets();
    const auto& nb = list_.neighbours();
    const double* v = geo_.volume.data();
    const double* x = geo_.position.data();
    for (std::size_t i = 0; i < div.size(); ++i) {
      double gxx = 0.0, gxy = 0.0, gyx = 0.0, gyy = 0.0, l = 0.0;
      for (int k = off[i]; k < off[i + 1]; ++k) {
        const int j = nb[k];
        const double s = -v[j] * pairs_[k].f;
        const double du = vel[2 * j] - vel[2 * i], dv = vel[2 * j + 1] - vel[2 * i + 1];
        const double wx = s * (x[2 * j] - x[2 * i]), wy = s * (x[2 * j + 1] - x[2 * i + 1]);
        gxx += du * wx;
        gxy += du * wy;
        gyx += dv * wx;
        gyy += dv * wy;
        l += v[j] * (a[i] - a[j]) * pairs_[k].f;
      }
      const double* m = geo_.l_inverse.data() + 3 * i;
      div[i] = gxx * m[0] + (gxy + gyx) * m[1] + gyy * m[2];
      lap[i] = 2.0 * l;
    }
  }

  // sp::adjoint_pressure_force: F_i = P_i S1_i + V_i S2_i with P_j = A_j q_j L_j^{-1}.
  void adjoint_force(const std::vector<double>& area, const std::vector<double>& q,
                     std::vector<double>& force) const {
    const auto& off = list_.offsets();
    const auto& nb = list_.neighbours();
    const double* v = geo_.volume.data();
    const double* x = geo_.position.data();
    const std::size_t n = q.size();
    std::vector<double> p(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) p[3 * i + c] = area[i] * q[i] * geo_.l_inverse[3 * i + c];
    }
    for (std::size_t i = 0; i < n; ++i) {
      double s1x = 0.0, s1y = 0.0, s2x = 0.0, s2y = 0.0;
      for (int k = off[i]; k < off[i + 1]; ++k) {
        const int j = nb[k];
        const double fx = pairs_[k].f * (x[2 * j] - x[2 * i]);
        const double fy = pairs_[k].f * (x[2 * j + 1] - x[2 * i + 1]);
        s1x += v[j] * fx;
        s1y += v[j] * fy;
        s2x += p[3 * j] * fx + p[3 * j + 1] * fy;
        s2y += p[3 * j + 1] * fx + p[3 * j + 2] * fy;
      }
      force[2 * i] = (p[3 * i] * s1x + p[3 * i + 1] * s1y) + v[i] * s2x;
      force[2 * i + 1] = (p[3 * i + 1] * s1x + p[3 * i + 2] * s1y) + v[i] * s2y;
    }
  }

  // sp::gradient (CSPM, eq. 16).
  void gradient(const std::vector<double>& a, std::vector<double>& grad) const {
    const auto& off = list_.offsets();
    const auto& nb = list_.neighbours();
    const double* v = geo_.volume.data();
    const double* x = geo_.position.data();
    for (std::size_t i = 0; i < a.size(); ++i) {
      double sx = 0.0, sy = 0.0;
      for (int k = off[i]; k < off[i + 1]; ++k) {
        const int j = nb[k];
        const double s = v[j] * (a[j] - a[i]) * -pairs_[k].f;
        sx += s * (x[2 * j] - x[2 * i]);
        sy += s * (x[2 * j + 1] - x[2 * i + 1]);
      }
      const double* m = geo_.l_inverse.data() + 3 * i;
      grad[2 * i] = m[0] * sx + m[1] * sy;
      grad[2 * i + 1] = m[1] * sx + m[2] * sy;
    }
  }

  // sp::volume_sum: sum_j V_j W_ij with the self term.
  void volume_sum(double w0, std::vector<double>& out) const {
    const auto& off = list_.offsets();
    const auto& nb = list_.neighbours();
    const double* v = geo_.volume.data();
    for (std::size_t i = 0; i < out.size(); ++i) {
      double s = v[i] * w0;
      for (int k = off[i]; k < off[i + 1]; ++k) s += v[nb[k]] * pairs_[k].w;
      out[i] = s;
    }
  }

  std::size_t skin_pairs() const {
    std::size_t zero = 0;
    for (const PairKernel& p : pairs_) zero += p.f == 0.0;
    return zero;
  }

 private:
  const sp::NeighbourList& list_;
  const sp::Geometry& geo_;
  std::vector<PairKernel> pairs_;
};

// Bit equality of two arrays, with the first differing index in the message.
::testing::AssertionResult same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return ::testing::AssertionFailure() << "sizes differ";
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (std::memcmp(&a[k], &b[k], sizeof(double)) != 0) {
      return ::testing::AssertionFailure()
             << "entry " << k << ": " << a[k] << " against " << b[k] << " (of " << a.size() << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

void check_all(const Initialised& s, double h_m, std::uint64_t seed) {
  const std::size_t n = s.particles.size();
  const ReferenceOperators ref(s.list(), s.geo(), h_m);
  // The list's skin (h to 1.1 h) holds about a sixth of its pairs: the test covers dropping them.
  ASSERT_GT(ref.skin_pairs(), s.list().pairs() / 20);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::vector<double> vel(2 * n), a(n), area(n);
  for (double& v : vel) v = uni(rng);
  for (double& v : a) v = 1e6 * uni(rng);
  for (std::size_t i = 0; i < n; ++i) area[i] = 1e-7 * (1.5 + uni(rng));

  std::vector<double> div(n), lap(n), div_ref(n), lap_ref(n);
  sp::divergence_laplacian(s.geo(), vel, a, div, lap);
  ref.divergence_laplacian(vel, a, div_ref, lap_ref);
  EXPECT_TRUE(same_bits(div, div_ref)) << "divergence";
  EXPECT_TRUE(same_bits(lap, lap_ref)) << "laplacian";
  std::vector<double> div_alone(n), lap_alone(n);
  sp::divergence(s.geo(), vel, div_alone);
  sp::laplacian(s.geo(), a, lap_alone);
  EXPECT_TRUE(same_bits(div_alone, div_ref)) << "divergence alone";
  EXPECT_TRUE(same_bits(lap_alone, lap_ref)) << "laplacian alone";

  std::vector<double> force(2 * n), force_ref(2 * n), work(3 * n);
  sp::adjoint_pressure_force(s.geo(), area, a, force, work);
  ref.adjoint_force(area, a, force_ref);
  EXPECT_TRUE(same_bits(force, force_ref)) << "adjoint force";

  std::vector<double> grad(2 * n), grad_ref(2 * n);
  sp::gradient(s.geo(), a, grad);
  ref.gradient(a, grad_ref);
  EXPECT_TRUE(same_bits(grad, grad_ref)) << "gradient";

  const double w0 = sp::WendlandC2(h_m).w0();
  std::vector<double> vs(n), vs_ref(n);
  sp::volume_sum(s.geo(), w0, vs);
  ref.volume_sum(w0, vs_ref);
  EXPECT_TRUE(same_bits(vs, vs_ref)) << "volume sum";
}

TEST(SpOperatorBits, MatchThePlainFormulasOverEveryListedPairOnTheRandomPacking) {
  check_all(Initialised(random_packing(), 0.0015), 0.0015, 3);
}

TEST(SpOperatorBits, MatchThePlainFormulasOverEveryListedPairOnAJitteredLattice) {
  // Free surfaces on all four sides: rows of every length, L_i projected at the corners.
  check_all(Initialised(jittered(30, 20, 0.0005, 0.3, 5), 0.00125), 0.00125, 4);
}

}  // namespace
}  // namespace rockcut::fluid::test
