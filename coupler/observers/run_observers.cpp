#include "observers/run_observers.hpp"

#include "observers/analytical_cutting.hpp"
#include "observers/calibration_summary.hpp"
#include "observers/cutting_summary.hpp"
#include "observers/energy_budget.hpp"
#include "observers/expected_error.hpp"
#include "observers/fracture_summary.hpp"
#include "observers/lag_check.hpp"
#include "observers/peclet.hpp"
#include "observers/pressure_nodes.hpp"

namespace rockcut::coupler {

void register_observers(const rockcut::Scene& scene, const TimePlan& plan,
                                      const ObserverInputs& inputs, RunObservers& observers) {
  // Pressure nodes need a fluid model with a pressure; others (prescribed_gradient, a third
  // party's) run without them.
  std::vector<PressureNodeBox> nodes;
  if (inputs.fluid_has_pressure) nodes = pressure_nodes(scene);
  if (scene.dem().has_tool()) {
    std::vector<std::string> node_names;
    for (const PressureNodeBox& n : nodes) node_names.push_back(n.name);
    observers.add(std::make_unique<CuttingSummary>(scene, std::move(node_names)));
    // After the cutting summary: its ratios read the summary's DEM forces.
    if (scene.has_rock()) observers.add(std::make_unique<AnalyticalCutting>(scene));
  }
  if (!nodes.empty()) {
    observers.add(std::make_unique<PressureNodeProbes>(std::move(nodes), inputs.dem_label));
  }
  if (scene.dem().has_loading_test()) {
    if (scene.dem().loading_test().kind() == "fracture") {
      observers.add(std::make_unique<FractureSummary>(scene));
    } else {
      observers.add(std::make_unique<CalibrationSummary>(scene));
    }
  }
  if (const auto pe = peclet_number(scene)) observers.add(std::make_unique<PecletReport>(*pe));
  const double dem_limit_s = smallest_limit_s(inputs.dem_limits);
  const double stiffness_limit_s = pore_fluid_stiffness_limit_s(inputs.fluid_limits);
  if (auto line = expected_error_line(scene, plan, dem_limit_s, stiffness_limit_s, inputs.program_dir)) {
    observers.add(std::make_unique<ExpectedErrorReport>(std::move(*line)));
  }
  if (scene.has_verification()) {
    try {
      observers.add(std::make_unique<VerificationCheck>(scene));
    } catch (const std::invalid_argument& e) {
      throw PlanError(e.what());
    }
  }
  observers.add(std::make_unique<EnergyReport>(scene.has_fluid() ? "pore fluid" : "external force"));
  // After the energy line: where in a cut the lag's correction did the pore fluid's dissipation.
  if (plan.lag_passivity && scene.dem().has_tool()) observers.add(std::make_unique<LagCheck>());
}

}  // namespace rockcut::coupler
