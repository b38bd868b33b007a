// The `implicit` pore-pressure model: the paper's model (sections 3.2-3.3) with backward Euler in
// time, for stiff diffusion (large D = M kappa / mu, small h). Unconditionally stable; each step
// solves one sparse symmetric positive definite system (sp/implicit_system.hpp, which also says how
// the cavitation clamp of eq. 22 is imposed). Instead of a stability limit it reports an accuracy
// limit, dt <= fluid.implicit.max_diffusion_number h^2 / D, so that the coupler's choice of the
// fluid step stays where the error study (docs/verification.md) measured it.
#pragma once

#include "sp/implicit_system.hpp"
#include "models/pore_pressure_model.hpp"

namespace rockcut::fluid::sp {

class ImplicitModel final : public PorePressureModel {
 public:
  explicit ImplicitModel(const SpParams& params);
  std::string name() const override { return "implicit"; }
  const ImplicitReport& last_solve() const { return last_; }

 private:
  StabilityLimit diffusion_limit() const override;
  void advance(double dt_s) override;
  void save_model_state(state::StateArchive& archive) const override;
  void load_model_state(const state::StateArchive& archive) override;
  void add_scalars(std::vector<std::pair<std::string, double>>& out) const override;

  ImplicitSystem system_;
  ImplicitReport last_;
};

}  // namespace rockcut::fluid::sp
