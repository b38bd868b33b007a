#include "run/pressure_nodes.hpp"

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

}  // namespace rockcut::coupler
