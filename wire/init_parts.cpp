#include "wire/init_parts.hpp"

namespace rockcut::wire {

void set_dem_part(const rockcut::Scene& scene, const std::string& scene_dir, Init& init) {
  DemConfig* part = init.mutable_dem();
  *part->mutable_dem() = scene.dem();
  part->set_scene_dir(scene_dir);
  part->set_coupled(scene.has_fluid());
}

void set_fluid_part(const rockcut::Scene& scene, const InitReply& dem_reply, Init& init) {
  FluidConfig* part = init.mutable_fluid();
  *part->mutable_fluid() = scene.fluid();
  part->set_water_depth_m(scene.water_depth_m());
  if (dem_reply.has_solid()) *part->mutable_solid() = dem_reply.solid();
}

}  // namespace rockcut::wire
