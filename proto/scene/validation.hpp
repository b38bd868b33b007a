// Checking a parsed scene against the field options of its schema (rockcut/options.proto).
#pragma once

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include <string>
#include <vector>

#include "rockcut/scene.pb.h"

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

/// What a module runs on the scene it is sent in Init: the same rules as validate() (the
/// coupler's), so a peer cannot skip them. Throws std::invalid_argument naming the first problems
/// in one line.
void validate_received(const rockcut::Scene& scene);

}  // namespace rockcut::scene
