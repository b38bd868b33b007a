// Registers `explicit`: the paper's pore-pressure model with forward Euler (sp/explicit_model.hpp).
#include "models/registry.hpp"
#include "sp/explicit_model.hpp"

namespace rockcut::fluid {
namespace {
const bool registered = register_model("explicit", [](const wire::FluidConfig& config) {
  return std::make_unique<sp::ExplicitModel>(sp::sp_params_from_config(config));
});
}  // namespace
}  // namespace rockcut::fluid
