// Registers `implicit`: the paper's pore-pressure model with backward Euler (sp/implicit_model.hpp).
#include "models/registry.hpp"
#include "sp/implicit_model.hpp"

namespace rockcut::fluid {
namespace {
const bool registered = register_model("implicit", [](const wire::FluidConfig& config) {
  return std::make_unique<sp::ImplicitModel>(sp::sp_params_from_config(config));
});
}  // namespace
}  // namespace rockcut::fluid
