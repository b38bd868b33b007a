#include "scene/source_map.hpp"

namespace rockcut::scene {
namespace {

namespace pb = google::protobuf;
using Tree = pb::TextFormat::ParseInfoTree;

int value_count(const pb::Message& m, const pb::FieldDescriptor* f) {
  const pb::Reflection& r = *m.GetReflection();
  return f->is_repeated() ? r.FieldSize(m, f) : (r.HasField(m, f) ? 1 : 0);
}

void fill(const pb::Message& message, const Tree& tree, const std::string& file, SourceMap& map) {
  const pb::Descriptor& type = *message.GetDescriptor();
  const pb::Reflection& r = *message.GetReflection();
  for (int i = 0; i < type.field_count(); ++i) {
    const pb::FieldDescriptor* field = type.field(i);
    const int count = value_count(message, field);
    if (count == 0) continue;
    // `f: [a, b]` is recorded once for all its values: then every value gets the first record.
    int recorded = 0;
    if (field->is_repeated())
      while (tree.GetLocation(field, recorded).line >= 0) ++recorded;
    std::vector<Location>& at = map.fields[field];
    for (int k = 0; k < count; ++k) {
      const int index = field->is_repeated() ? (recorded == count ? k : 0) : -1;
      const auto location = tree.GetLocation(field, index);
      at.push_back(location.line < 0 ? Location{} : Location{file, location.line + 1, location.column + 1});
      if (field->cpp_type() != pb::FieldDescriptor::CPPTYPE_MESSAGE) continue;
      const int own = field->is_repeated() ? k : -1;
      const Tree* nested = tree.GetTreeForNested(field, own);
      if (nested == nullptr) continue;
      const pb::Message& child = field->is_repeated() ? r.GetRepeatedMessage(message, field, k)
                                                      : r.GetMessage(message, field);
      fill(child, *nested, file, map.child_or_create(field, own));
    }
  }
}

}  // namespace

const Location* SourceMap::find(const Field* field, int index) const {
  const auto it = fields.find(field);
  if (it == fields.end()) return nullptr;
  const std::size_t k = index < 0 ? 0 : static_cast<std::size_t>(index);
  if (k >= it->second.size() || it->second[k].line <= 0) return nullptr;
  return &it->second[k];
}

const SourceMap* SourceMap::child(const Field* field, int index) const {
  const auto it = nested.find({field, index});
  return it == nested.end() ? nullptr : it->second.get();
}

SourceMap& SourceMap::child_or_create(const Field* field, int index) {
  std::unique_ptr<SourceMap>& slot = nested[{field, index}];
  if (!slot) slot = std::make_unique<SourceMap>();
  return *slot;
}

std::unique_ptr<SourceMap> source_map(const pb::Message& message, const Tree& tree,
                                      const std::string& file) {
  auto map = std::make_unique<SourceMap>();
  fill(message, tree, file, *map);
  return map;
}

void overlay(pb::Message& base, SourceMap& base_map, pb::Message& layer, SourceMap& layer_map) {
  const pb::Descriptor& type = *base.GetDescriptor();
  const pb::Reflection& r = *base.GetReflection();
  for (int i = 0; i < type.field_count(); ++i) {
    const pb::FieldDescriptor* field = type.field(i);
    if (value_count(layer, field) == 0) continue;  // not written in this layer: the base's stays
    if (const auto at = layer_map.fields.find(field); at != layer_map.fields.end())
      base_map.fields[field] = at->second;
    else
      base_map.fields.erase(field);
    if (!field->is_repeated() && field->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
      overlay(*r.MutableMessage(&base, field), base_map.child_or_create(field, -1),
              *r.MutableMessage(&layer, field), layer_map.child_or_create(field, -1));
      continue;
    }
    // A scalar replaces the base's value; a repeated field replaces the base's whole list.
    r.SwapFields(&base, &layer, {field});
    for (auto it = base_map.nested.begin(); it != base_map.nested.end();)
      it = it->first.first == field ? base_map.nested.erase(it) : std::next(it);
    for (auto& [key, map] : layer_map.nested)
      if (key.first == field) base_map.nested[key] = std::move(map);
  }
}

}  // namespace rockcut::scene
