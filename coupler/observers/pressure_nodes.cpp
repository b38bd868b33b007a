#include "observers/pressure_nodes.hpp"

#include "wire/module_client.hpp"

namespace rockcut::coupler {

std::vector<PressureNodeBox> pressure_nodes(const rockcut::Scene& scene) {
  if (!scene.has_fluid() || !scene.dem().has_tool()) return {};
  const rockcut::Tool& tool = scene.dem().tool();
  std::vector<PressureNodeBox> nodes;
  for (const rockcut::PressureNode& n : tool.pressure_nodes()) {
    nodes.push_back({n.name(), n.offset_m().x(), n.offset_m().y(), n.size_m()});
  }
  if (nodes.empty()) {
    // Paper section 4: "Node 1 is located exactly at the tool tip, node 2 is 12.5 mm in front and
    // 10 mm above the tool tip and node 3 is 30 mm in front of the tool tip", all 2.5 mm wide.
    nodes = {{"p1", 0.0, 0.0, 0.0025}, {"p2", 0.0125, 0.010, 0.0025}, {"p3", 0.030, 0.0, 0.0025}};
  }
  return nodes;
}

void place_probes(const std::vector<PressureNodeBox>& nodes, double tip_x_m, double tip_y_m,
                  wire::FluidStep& step) {
  step.clear_probes();
  for (const PressureNodeBox& n : nodes) {
    wire::Probe* p = step.add_probes();
    const double cx = tip_x_m + n.offset_x_m, cy = tip_y_m + n.offset_y_m, half = 0.5 * n.size_m;
    p->set_name(n.name);
    p->set_x_min_m(cx - half);
    p->set_x_max_m(cx + half);
    p->set_y_min_m(cy - half);
    p->set_y_max_m(cy + half);
  }
}

void PressureNodeProbes::start(Summary&, std::vector<std::string>& report) {
  report.push_back("nodes      " + std::to_string(nodes_.size()) +
                   " pressure nodes moving with the tool");
}

void PressureNodeProbes::prepare_fluid_step(const wire::Kinematics& kinematics,
                                            wire::FluidStep& step) {
  const auto tip_x = kinematics.scalars().find("tool_tip_x_m");
  const auto tip_y = kinematics.scalars().find("tool_tip_y_m");
  if (tip_x == kinematics.scalars().end() || tip_y == kinematics.scalars().end()) {
    throw wire::ModuleFailure(dem_label_, "reports no tool tip with its Kinematics");
  }
  place_probes(nodes_, tip_x->second, tip_y->second, step);
}

}  // namespace rockcut::coupler
