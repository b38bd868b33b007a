// Fluid models by name. Adding a model is a new file that registers itself: no central list.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "models/fluid_model.hpp"
#include "rockcut/scene.pb.h"

namespace rockcut::fluid {

using ModelFactory = std::function<std::unique_ptr<FluidModel>(const rockcut::Scene& scene)>;

bool register_model(const std::string& name, ModelFactory factory);
/// Builds the model the scene names; throws std::invalid_argument listing the known models.
std::unique_ptr<FluidModel> make_model(const rockcut::Scene& scene);
std::vector<std::string> model_names();

}  // namespace rockcut::fluid
