// Where each field of a parsed message was written. A scene composed from several files (`base:`)
// keeps, for every value, the file, line and column of the layer that wrote it, so that validation
// reports a problem where the user wrote the value, also in a base.
#pragma once

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scene/overrides.hpp"

namespace rockcut::scene {

/// Mirrors a message tree: the locations of each field's values and the maps of its nested messages.
struct SourceMap {
  using Field = google::protobuf::FieldDescriptor;
  /// One location for a singular field, one per element of a repeated field.
  std::map<const Field*, std::vector<Location>> fields;
  /// The maps of nested messages, by (field, element index; -1 for a singular field).
  std::map<std::pair<const Field*, int>, std::unique_ptr<SourceMap>> nested;

  /// Where value `index` (-1: singular) of `field` was written; nullptr when unknown.
  const Location* find(const Field* field, int index) const;
  /// The map of a nested message; nullptr when unknown.
  const SourceMap* child(const Field* field, int index) const;
  /// The map of a nested message, created empty when absent.
  SourceMap& child_or_create(const Field* field, int index);
};

/// The source map of `message` as parsed from `file`, from the parser's `tree`.
std::unique_ptr<SourceMap> source_map(const google::protobuf::Message& message,
                                      const google::protobuf::TextFormat::ParseInfoTree& tree,
                                      const std::string& file);

/// Lays `layer` over `base`, keeping both source maps in step:
///   - a message field the layer writes merges field by field (recursively);
///   - a scalar field the layer writes replaces the base's value;
///   - a repeated field the layer writes (one element or more) replaces the base's whole list
///     (replace on mention, not protobuf's MergeFrom, which would append).
/// Fields the layer does not write keep the base's value and location. `layer` is left unspecified
/// (its values are moved, not copied).
void overlay(google::protobuf::Message& base, SourceMap& base_map, google::protobuf::Message& layer,
             SourceMap& layer_map);

}  // namespace rockcut::scene
