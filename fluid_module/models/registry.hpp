// Fluid models by name. Adding a model is a new file that registers itself: no central list.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "models/fluid_model.hpp"
#include "rockcut/wire.pb.h"

namespace rockcut::fluid {

/// A model is built from the fluid's part of the scene (Init.fluid): the scene's fluid block, the
/// water depth and the solid's properties the DEM sent.
using ModelFactory = std::function<std::unique_ptr<FluidModel>(const wire::FluidConfig& config)>;

bool register_model(const std::string& name, ModelFactory factory);
/// Builds the model fluid.model names; throws std::invalid_argument listing the known models.
std::unique_ptr<FluidModel> make_model(const wire::FluidConfig& config);
std::vector<std::string> model_names();

}  // namespace rockcut::fluid
