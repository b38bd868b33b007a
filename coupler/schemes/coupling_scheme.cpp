#include "schemes/coupling_scheme.hpp"

#include "schemes/dry_scheme.hpp"
#include "schemes/half_step_exchange.hpp"

namespace rockcut::coupler {

std::unique_ptr<CouplingScheme> make_coupling_scheme(const rockcut::Scene& scene,
                                                     const TimePlan& plan, RunModules& modules,
                                                     const RunObservers& observers) {
  if (scene.has_fluid()) return std::make_unique<HalfStepExchange>(plan, modules, observers);
  return std::make_unique<DryScheme>(plan, modules);
}

}  // namespace rockcut::coupler
