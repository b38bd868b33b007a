// The pressure nodes of the paper's figure 7: boxes that move with the tool, in which the fluid
// averages p - p_hydro every exchange (wire Probe). The coupler places them from the tool tip the
// DEM reports at the split point of the step, so they sit where the tool is when the fluid works.
#pragma once

#include <string>
#include <vector>

#include "rockcut/scene.pb.h"
#include "rockcut/wire.pb.h"

namespace rockcut::coupler {

struct PressureNodeBox {
  std::string name;
  double offset_x_m = 0.0, offset_y_m = 0.0;  ///< centre relative to the tool tip
  double size_m = 0.0025;
};

/// The scene's dem.tool.pressure_nodes, or the paper's p1-p3 when it names none. Empty for a
/// scene without a tool or without a fluid.
std::vector<PressureNodeBox> pressure_nodes(const rockcut::Scene& scene);

/// Sets `step.probes` to the nodes around the tip at (tip_x_m, tip_y_m).
void place_probes(const std::vector<PressureNodeBox>& nodes, double tip_x_m, double tip_y_m,
                  wire::FluidStep& step);

}  // namespace rockcut::coupler
