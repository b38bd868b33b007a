// The engineer's analytical cutting models beside the DEM's cut: for a cutting scene with a `rock`
// block, summary.json's `analytical_*` keys give each model's force per metre at the scene's tool
// angle, cut depth and water depth, and the DEM's mean and peak horizontal force over it
// (docs/cutting_models.md, docs/outputs.md). The models (coupler/cutting_models/) depend only on the
// scene, so they are evaluated once; the ratios are taken at the end from the cutting summary's
// keys (this observer is registered after CuttingSummary).
//
// Inputs: rock.ucs_pa, bts_pa, cohesion_pa, friction_angle_deg, nishimatsu_exponent (or
// Nishimatsu's fit); the rock-tool friction angle atan(dem.contact.friction), the friction of the
// tool's contacts in the DEM; dem.tool.cutting_angle_deg (Miedema's blade angle), cutting_depth_m
// and face_length_m (the blade height for the hyperbaric model's W2: face length x sin(alpha)); the
// water depth and, for a scene with a fluid, its atmospheric pressure, water density, gravity and
// cavitation pressure (the cavitation bound of the under-pressure). A dry scene has no pore water:
// its hyperbaric force is the drained (Merchant) force, under-pressure 0.
#pragma once

#include <string>
#include <vector>

#include "cutting_models/cutting_force.hpp"
#include "observers/run_observer.hpp"
#include "rockcut/scene.pb.h"

namespace rockcut::coupler {

class AnalyticalCutting : public RunObserver {
 public:
  /// `scene` must have a tool and a rock block.
  explicit AnalyticalCutting(const rockcut::Scene& scene);
  /// The models' keys, and the DEM/model ratios against the keys `summary` already holds.
  void write(Summary& summary) const;
  bool finish(const RunClock&, Summary& summary, bool) override {
    write(summary);
    return true;
  }

  struct Model {
    std::string name;  ///< evans, nishimatsu, merchant, hyperbaric
    cutting_models::CuttingForce force;
  };
  const std::vector<Model>& models() const { return models_; }

 private:
  std::vector<Model> models_;
  std::vector<std::pair<std::string, SummaryValue>> extra_;  // shear angles, n, dp, mode, inputs
};

}  // namespace rockcut::coupler
