// From scene to core: the DEM's edge, where scene blocks become plain structs and cross-field
// checks name the offending field. Physics classes never see the scene.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/dem_system.hpp"
#include "core/guards.hpp"
#include "core/stability.hpp"
#include "rockcut/scene.pb.h"
#include "rockcut/wire.pb.h"

namespace rockcut::dem {

/// The chisel as placed in the specimen.
struct ToolPlacement {
  bool present = false;
  std::uint32_t body = 0;
  double tip_x0_m = 0.0, tip_y_m = 0.0;  ///< tip at t = 0
  double velocity_m_s = 0.0;
  double width_m = 0.0;
  double specimen_left_m = 0.0;   ///< where the cut starts
  double steady_after_m = 0.0;    ///< travel into the specimen after which the cut is steady
};

/// A platen test as placed around the specimen.
struct LoadingRig {
  bool present = false;
  bool ucs = true;                      ///< UCS or biaxial specimen; else Brazilian or fracture
  bool biaxial = false;                 ///< a confining stress on the sides
  bool side_walls = false;              ///< biaxial by servo-controlled walls; else a membrane
  std::uint32_t left_wall = 0, right_wall = 0;  ///< the servo-controlled side walls
  std::uint32_t top = 0, bottom = 0;    ///< wall bodies
  double height0_m = 0.0, width0_m = 0.0;
  std::vector<std::uint32_t> left_strip, right_strip;  ///< discs whose mean x gives the width
  double strip_width0_m = 0.0;                          ///< that width at t = 0
  /// UCS: discs within one largest radius of a quarter and three quarters of the height, whose
  /// mean y give the gauge length (a strain gauge on the specimen's middle half, away from the
  /// ends, which the platens crush and seat first).
  std::vector<std::uint32_t> lower_gauge, upper_gauge;
  double gauge_length0_m = 0.0;  ///< that length at t = 0; 0 without a gauge
  /// clamp_end_layers (UCS: the discs within one largest diameter of the top and bottom) or
  /// loading_arc_deg (Brazilian: the rim's discs within the loading arcs) move with the platens as
  /// DemSystem::clamped_group(top_layer_group) and (bottom_layer_group).
  bool clamped_ends = false;
  std::size_t top_layer_group = 0, bottom_layer_group = 0;
  /// `fracture`: the end layers pull the double-edge-notched specimen apart; the ligament is the
  /// width left between the notches (loading_test.notch_depth_ratio).
  bool fracture = false;
  double ligament_m = 0.0;
};

/// Mean x (axis 0) or y (axis 1) of the discs in `strip`; 0 for an empty strip.
inline double mean_coordinate(const Particles& p, const std::vector<std::uint32_t>& strip, int axis) {
  double sum = 0.0;
  for (std::uint32_t i : strip) sum += p.position[2 * i + axis];
  return strip.empty() ? 0.0 : sum / static_cast<double>(strip.size());
}

struct DemSetup {
  std::unique_ptr<DemSystem> system;
  ToolPlacement tool;
  LoadingRig rig;
  CriticalStep critical;                      ///< none (dt 0) without springs
  GuardLimits guards;
  double initial_energy_j = 0.0;              ///< kinetic + strain at t = 0 [J/m] (energy budget)
  std::vector<std::uint32_t> initial_bonds;   ///< per particle, for damage
  std::string specimen_report;                ///< porosity, coordination, ... for the log
};

/// Builds the DEM of the scene's `dem` block. Throws std::invalid_argument naming the field for
/// inconsistent input (radius_min_m > radius_max_m, a tool outside the specimen, ...).
/// The damping the scene's dem.damping asks for, as the step loop takes it: alpha_d of eq. 10 and
/// the dashpots' zeta, each 0 when the model leaves it out. Throws std::invalid_argument when both
/// damping_ratio and restitution are given.
struct DampingChoice {
  double local_coefficient = 0.0;
  double damping_ratio = 0.0;
};
DampingChoice damping_choice(const rockcut::Dem& dem);

DemSetup build_dem(const rockcut::Dem& dem);

/// What the fluid needs to know of this solid (wire.proto, SolidProperties): sent in InitReply
/// and forwarded by the coupler to the fluid.
rockcut::wire::SolidProperties solid_properties(const rockcut::Dem& dem);

}  // namespace rockcut::dem
