#include "models/registry.hpp"

#include <map>
#include <stdexcept>

namespace rockcut::fluid {

namespace {
std::map<std::string, ModelFactory>& factories() {
  static std::map<std::string, ModelFactory> map;  // function-local: safe during static init
  return map;
}
}  // namespace

bool register_model(const std::string& name, ModelFactory factory) {
  factories()[name] = std::move(factory);
  return true;
}

std::vector<std::string> model_names() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : factories()) names.push_back(name);
  return names;
}

std::unique_ptr<FluidModel> make_model(const wire::FluidConfig& config) {
  const std::string& name = config.fluid().model();
  auto it = factories().find(name);
  if (it == factories().end()) {
    std::string known;
    for (const auto& n : model_names()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("fluid.model \"" + name + "\" is not a model of fluid_module; " +
                                "it offers: " + known);
  }
  return it->second(config);
}

}  // namespace rockcut::fluid
