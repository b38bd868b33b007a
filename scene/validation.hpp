// Checking a parsed scene against the field options of its schema (rockcut/options.proto).
#pragma once

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include <string>
#include <vector>

#include "rockcut/scene.pb.h"
#include "rockcut/wire.pb.h"

#include "scene/overrides.hpp"
#include "scene/scene_loader.hpp"
#include "scene/source_map.hpp"

namespace rockcut::scene {

/// Walks the whole message tree by reflection and reports every field that breaks its
/// (required), (min), (max), (greater_than) or (choices) option, or is a NaN or infinite number.
/// Positions come from `sites` for overridden fields, else from `map` (where the file, or a base,
/// wrote the value); problems of the whole scene are reported at the start of `file`.
std::vector<Diagnostic> validate(const google::protobuf::Message& root, const std::string& file,
                                 const SourceMap* map, const OverrideSites& sites);

/// What a module runs on its part of the scene sent in Init: the same rules as validate() (the
/// coupler's), so a peer cannot skip them, on that part alone. Field paths read as in the scene
/// ("dem.lattice.radius_m", "fluid.threads", "water_depth_m"); the SolidProperties the fluid is
/// forwarded read "solid.*". The DEM's part also gets the particle budget
/// (scene/particle_budget.hpp). Throws std::invalid_argument naming the first problems in one line.
void validate_received(const rockcut::wire::DemConfig& config);
void validate_received(const rockcut::wire::FluidConfig& config);

}  // namespace rockcut::scene
