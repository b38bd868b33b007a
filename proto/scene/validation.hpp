// Checking a parsed scene against the field options of its schema (rockcut/options.proto).
#pragma once

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include <string>
#include <vector>

#include "rockcut/scene.pb.h"

#include "scene/overrides.hpp"
#include "scene/scene_loader.hpp"

namespace rockcut::scene {

/// Walks the whole message tree by reflection and reports every field that breaks its
/// (required), (min), (max), (greater_than) or (choices) option, or is a NaN or infinite number.
/// Positions come from `tree` (the parse of `file`) or, for overridden fields, from `sites`.
std::vector<Diagnostic> validate(const google::protobuf::Message& root, const std::string& file,
                                 const google::protobuf::TextFormat::ParseInfoTree* tree,
                                 const OverrideSites& sites);

/// What a module runs on the scene it is sent in Init: the same rules as validate() (the
/// coupler's), so a peer cannot skip them. Throws std::invalid_argument naming the first problems
/// in one line.
void validate_received(const rockcut::Scene& scene);

}  // namespace rockcut::scene
