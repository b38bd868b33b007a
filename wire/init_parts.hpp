// The part of a scene each module is sent at Init (wire.proto: DemConfig, FluidConfig): the DEM
// gets the dem block, the fluid the fluid block and the water depth. Neither gets the whole scene;
// what the fluid needs of the solid comes from the DEM's InitReply (SolidProperties).
#pragma once

#include <string>

#include "rockcut/scene.pb.h"
#include "rockcut/wire.pb.h"

namespace rockcut::wire {

/// Sets init's DEM part: scene.dem, the scene's directory (the DEM reads its packing file only
/// there and below) and whether the scene has a fluid (the DEM then needs its force).
void set_dem_part(const rockcut::Scene& scene, const std::string& scene_dir, Init& init);

/// Sets init's fluid part: scene.fluid, scene.water_depth_m and `solid`, the DEM's
/// InitReply.solid (left out when the DEM sent none: a model that needs it refuses the Init).
void set_fluid_part(const rockcut::Scene& scene, const InitReply& dem_reply, Init& init);

}  // namespace rockcut::wire
