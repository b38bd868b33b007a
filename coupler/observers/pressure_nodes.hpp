// The pressure nodes of the paper's figure 7: boxes that move with the tool, in which the fluid
// averages p - p_hydro every exchange (wire Probe). The coupler places them from the tool tip the
// DEM reports at the split point of the step, so they sit where the tool is when the fluid works.
#pragma once

#include <string>
#include <vector>

#include "observers/run_observer.hpp"
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

/// The pressure nodes of a saturated cut: probes placed around the tool tip in every recorded
/// fluid step (the fluid reports fluid_probe_<node>_pa; observers/cutting_summary.hpp averages it).
class PressureNodeProbes : public RunObserver {
 public:
  /// `dem_label`: the DEM, blamed when its kinematics carry no tool tip.
  PressureNodeProbes(std::vector<PressureNodeBox> nodes, std::string dem_label)
      : nodes_(std::move(nodes)), dem_label_(std::move(dem_label)) {}
  void start(Summary& summary, std::vector<std::string>& report) override;
  void prepare_fluid_step(const wire::Kinematics& kinematics, wire::FluidStep& step) override;

 private:
  std::vector<PressureNodeBox> nodes_;
  std::string dem_label_;
};

}  // namespace rockcut::coupler
