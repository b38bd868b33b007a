// --set dotted.path=value: changing any scalar field of a parsed scene from the command line.
#pragma once

#include <google/protobuf/message.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene_loader.hpp"

namespace rockcut::scene {

/// A position in the file or in an override (1-based).
struct Location {
  std::string file;
  int line = 0;
  int column = 0;
};

/// Where an override set a field (or created a block), keyed by (message, field): validation
/// reports problems of overridden values there rather than in the file.
using OverrideSites =
    std::map<std::pair<const google::protobuf::Message*, const google::protobuf::FieldDescriptor*>,
             Location>;

/// Applies each "a.b.c=value" to `root` in order, creating absent blocks on the way. A bad override
/// is reported (file "--set", line = its 1-based index, column = the offending part) and skipped.
std::vector<Diagnostic> apply_overrides(const std::vector<std::string>& overrides,
                                        google::protobuf::Message& root, OverrideSites& sites);

}  // namespace rockcut::scene
