// `prescribed_gradient`: a pressure field with the same gradient everywhere. The force on a disc of
// unit thickness is -grad p * pi r^2 (paper eq. 21 with d = 2r, w = 1). It needs no kinematics, so
// none are sent: it exists to verify the coupling loop against x0 + v0 t + a t^2 / 2.
#include <numbers>
#include <stdexcept>

#include "models/registry.hpp"

namespace rockcut::fluid {

namespace {

class PrescribedGradient final : public FluidModel {
 public:
  explicit PrescribedGradient(const rockcut::PrescribedGradient& params)
      : grad_x_pa_m_(params.pressure_gradient_pa_m().x()),
        grad_y_pa_m_(params.pressure_gradient_pa_m().y()) {}

  std::string name() const override { return "prescribed_gradient"; }
  std::vector<std::string> needs() const override { return {}; }
  std::vector<std::string> needs_static() const override { return {"radius"}; }
  std::vector<std::string> provides() const override { return {}; }
  std::vector<StabilityLimit> limits() const override { return {}; }
  bool supplies_energy() const override { return true; }  // a prescribed field, like gravity

  void initialise(const StaticData& data) override {
    radius_.assign(data.radius.begin(), data.radius.end());
  }

  void step(double, double, const Kinematics&, std::span<double> force) override {
    for (std::size_t i = 0; i < radius_.size(); ++i) {
      const double area = std::numbers::pi * radius_[i] * radius_[i];  // [m^2 per m thickness]
      force[2 * i] = -grad_x_pa_m_ * area;
      force[2 * i + 1] = -grad_y_pa_m_ * area;
    }
  }

  void output(const std::string& field, std::vector<double>&) const override {
    throw std::invalid_argument("prescribed_gradient provides no field '" + field + "'");
  }

  // A field fixed by the scene: nothing evolves.
  void save_state(state::StateArchive&) const override {}
  void load_state(const state::StateArchive&) override {}

 private:
  double grad_x_pa_m_;
  double grad_y_pa_m_;
  std::vector<double> radius_;
};

const bool registered = register_model("prescribed_gradient", [](const wire::FluidConfig& config) {
  if (!config.fluid().has_prescribed_gradient()) {
    throw std::invalid_argument(
        "fluid.model is \"prescribed_gradient\" but the block fluid.prescribed_gradient is missing");
  }
  return std::make_unique<PrescribedGradient>(config.fluid().prescribed_gradient());
});

}  // namespace

}  // namespace rockcut::fluid
