// The `explicit` pore-pressure model: the paper's scheme (sections 3.2-3.3), forward Euler in
// time.
//
// Stability: forward Euler on the eq. 20 Laplacian is stable while dt D rho <= 2, where rho is the
// spectral radius of the discrete Laplacian; rho h^2 depends only weakly on the packing.
// tests/fluid/laplacian_stability_test.cpp measures C_crit = 2 / (rho h^2) by power iteration on
// lattices and random packings with h / spacing from 2 to 5: C_crit lies between 0.063 and 0.093,
// smallest at the largest h / spacing, where the operator approaches its continuum limit. The
// model uses C = 0.05, 21 % below the smallest measured value, reports dt <= C h^2 / D in the
// handshake (so the coupler chooses its fluid step from it) and refuses a longer step. The
// consistent Laplacian (fluid.laplacian, sp/consistent_laplacian.hpp) measures 0.058-0.088: C
// stays 13 % below it.
#pragma once

#include "models/pore_pressure_model.hpp"

namespace rockcut::fluid::sp {

/// dt <= kExplicitStabilityC h^2 / D.
inline constexpr double kExplicitStabilityC = 0.05;

class ExplicitModel final : public PorePressureModel {
 public:
  explicit ExplicitModel(const SpParams& params);
  std::string name() const override { return "explicit"; }
  double dt_max_s() const { return dt_max_s_; }

 private:
  StabilityLimit diffusion_limit() const override;
  void advance(double dt_s) override;
  double dt_max_s_;
};

}  // namespace rockcut::fluid::sp
