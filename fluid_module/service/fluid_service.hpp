// The fluid module's protocol handler: builds the scene's model, and answers FluidStep with the
// force array. Any model registered in models/ is reachable by name.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "models/fluid_model.hpp"
#include "wire/module_server.hpp"

namespace rockcut::fluid {

class FluidService final : public wire::ModuleHandler {
 public:
  wire::ModuleKind kind() const override { return wire::MODULE_KIND_FLUID; }
  std::string name() const override { return "fluid_module"; }
  std::string version() const override;
  std::vector<std::string> models() const override;
  void handle(const wire::Message& request, wire::Message& reply) override;

 private:
  void init(const wire::Message& request, wire::Message& reply);
  void step(const wire::Message& request, wire::Message& reply);
  /// Sets result.guard when a force is NaN or Inf (the state is no longer physical).
  void guard_not_finite(double time_s, std::span<const double> position,
                        wire::FluidResult& result) const;
  void frame(const wire::FrameRequest& request, wire::Message& reply);
  /// Checkpoint and restart: the model's state (FluidModel::save_state) and the service's own.
  void save_state(wire::Message& reply);
  void load_state(const wire::Message& request, wire::Message& reply);
  FluidModel& model();

  std::unique_ptr<FluidModel> model_;
  std::vector<std::string> needs_;  ///< what the model needs per exchange
  // "displacement" is x^n - x^{n-N}, the difference of this and the last exchange's positions,
  // which the fluid receives anyway. It derives it here instead of asking the DEM for it: the
  // same subtraction of the same doubles, so the same bits, and a third fewer bytes on the wire
  // each way.
  bool derive_displacement_ = false;
  std::vector<double> previous_position_;  ///< positions of the last exchange (at first: Init's)
  std::vector<double> displacement_;
  std::size_t particle_count_ = 0;
  std::vector<double> force_;
  std::vector<double> self_stiffness_;  ///< K_ii [Pa], 3 per particle, where the coupling asks
  std::vector<double> output_;
  std::vector<std::pair<std::string, double>> scalars_;
};

}  // namespace rockcut::fluid
