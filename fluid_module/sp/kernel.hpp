// The Wendland C2 kernel in 2D (paper eq. 18; Wendland 1995) with support radius h:
//   W(R) = 7 / (pi h^2) (1 - R)^4 (1 + 4 R)  for R = r / h <= 1, else 0.
// The paper prints 7 / pi^2: a typo. 7 / (pi h^2) makes the integral of W over the plane 1
// (DESIGN section 4; tests/fluid/kernel_neighbours_test.cpp checks it).
//
// Every SP operator here needs the kernel gradient only through
//   grad_i W_ij = F(r_ij) (x_i - x_j),   F(r) = (1/r) dW/dr = -140 / (pi h^4) (1 - R)^3,
// which stays finite at r = 0, so coincident particles need no special case.
#pragma once

#include <cmath>
#include <numbers>

namespace rockcut::fluid::sp {

class WendlandC2 {
 public:
  explicit WendlandC2(double h_m)
      : h_(h_m), inv_h_(1.0 / h_m), sigma_(7.0 / (std::numbers::pi * h_m * h_m)),
        f_scale_(-20.0 * sigma_ / (h_m * h_m)) {}

  double support_m() const { return h_; }

  /// W(0) [1/m^2]: the self term of every kernel sum.
  double w0() const { return sigma_; }

  // Beyond the support (R >= 1) the factor (1 - R) is clamped to 0, which zeroes W and F without
  // a branch (a fifth of the listed pairs lie in the neighbour skin, at random). clamp() is
  // (t + |t|) / 2, exact in floating point; GCC turned both std::max(0.0, t) and t > 0 ? t : 0
  // into a mispredicted branch here (measured: the pair pass 1.5x slower).
  static double clamp(double t) { return 0.5 * (t + std::abs(t)); }

  /// W(r) [1/m^2] for r [m] (0 beyond the support).
  double w(double r_m) const {
    const double R = r_m * inv_h_;
    const double a = clamp(1.0 - R);
    return sigma_ * a * a * a * a * (1.0 + 4.0 * R);
  }

  /// W(r) and F(r) together, sharing the powers of (1 - R).
  void w_and_f(double r_m, double& w, double& f) const {
    const double R = r_m * inv_h_;
    const double a = clamp(1.0 - R), a3 = a * a * a;
    w = sigma_ * a3 * a * (1.0 + 4.0 * R);
    f = f_scale_ * a3;
  }

  /// F(r) = W'(r) / r [1/m^4] (<= 0; 0 beyond the support).
  double f(double r_m) const {
    const double a = clamp(1.0 - r_m * inv_h_);
    return f_scale_ * a * a * a;
  }

 private:
  double h_, inv_h_, sigma_, f_scale_;
};

}  // namespace rockcut::fluid::sp
