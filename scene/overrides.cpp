#include "scene/overrides.hpp"

#include <google/protobuf/io/tokenizer.h>

#include <charconv>
#include <cstdint>
#include <limits>
#include <optional>
#include <variant>

#include "scene/format.hpp"
#include "scene/nearest_name.hpp"

namespace rockcut::scene {
namespace {

namespace pb = google::protobuf;

using Scalar = std::variant<std::int64_t, std::uint64_t, double, bool, std::string,
                            const pb::EnumValueDescriptor*>;

/// A piece of an override with its 1-based column in the argument.
struct Part {
  std::string_view text;
  int column;
};

Part trimmed(Part part) {
  while (!part.text.empty() && part.text.front() == ' ') {
    part.text.remove_prefix(1);
    ++part.column;
  }
  while (!part.text.empty() && part.text.back() == ' ') part.text.remove_suffix(1);
  return part;
}

std::vector<Part> split_path(Part path) {
  std::vector<Part> parts;
  for (std::size_t start = 0;;) {
    const std::size_t dot = path.text.find('.', start);
    const std::size_t end = dot == std::string_view::npos ? path.text.size() : dot;
    parts.push_back({path.text.substr(start, end - start), path.column + static_cast<int>(start)});
    if (dot == std::string_view::npos) return parts;
    start = dot + 1;
  }
}

template <class T>
std::optional<T> parse_whole(std::string_view text) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// Reads `text` as a value of `field`'s type; on failure says why in `error`.
std::optional<Scalar> parse_scalar(const pb::FieldDescriptor& field, std::string_view text,
                                   std::string& error) {
  const std::string quoted = std::string(1, '"').append(text) + '"';
  switch (field.cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_INT32:
    case pb::FieldDescriptor::CPPTYPE_INT64: {
      const auto value = parse_whole<std::int64_t>(text);
      const bool is32 = field.cpp_type() == pb::FieldDescriptor::CPPTYPE_INT32;
      if (value && (!is32 || (*value >= std::numeric_limits<std::int32_t>::min() &&
                              *value <= std::numeric_limits<std::int32_t>::max())))
        return *value;
      error = quoted + " is not a valid " + field.type_name() + " (a whole number)";
      return std::nullopt;
    }
    case pb::FieldDescriptor::CPPTYPE_UINT32:
    case pb::FieldDescriptor::CPPTYPE_UINT64: {
      const auto value = parse_whole<std::uint64_t>(text);
      const bool is32 = field.cpp_type() == pb::FieldDescriptor::CPPTYPE_UINT32;
      if (value && (!is32 || *value <= std::numeric_limits<std::uint32_t>::max())) return *value;
      error = quoted + " is not a valid " + field.type_name() + " (a whole number >= 0)";
      return std::nullopt;
    }
    case pb::FieldDescriptor::CPPTYPE_DOUBLE:
    case pb::FieldDescriptor::CPPTYPE_FLOAT: {
      if (const auto value = parse_whole<double>(text)) return *value;
      error = quoted + " is not a valid " + field.type_name() + " (a number such as 2.5 or 1e-3)";
      return std::nullopt;
    }
    case pb::FieldDescriptor::CPPTYPE_BOOL:
      if (text == "true" || text == "1") return true;
      if (text == "false" || text == "0") return false;
      error = quoted + " is not a valid bool; use true, false, 1 or 0";
      return std::nullopt;
    case pb::FieldDescriptor::CPPTYPE_ENUM: {
      const pb::EnumDescriptor& type = *field.enum_type();
      if (const auto* value = type.FindValueByName(std::string(text))) return value;
      std::vector<std::string> names;
      for (int i = 0; i < type.value_count(); ++i) names.push_back(type.value(i)->name());
      error = quoted + " is not a value of " + type.full_name() + "; choose one of: " +
              join(names, ", ") + did_you_mean(text, names);
      return std::nullopt;
    }
    case pb::FieldDescriptor::CPPTYPE_STRING: {
      const bool starts_quoted = !text.empty() && (text.front() == '"' || text.front() == '\'');
      if (!starts_quoted) return std::string(text);
      if (text.size() < 2 || text.back() != text.front()) {
        error = "unterminated quoted string " + std::string(text);
        return std::nullopt;
      }
      std::string value;
      pb::io::Tokenizer::ParseString(std::string(text), &value);  // handles the C escapes
      return value;
    }
    case pb::FieldDescriptor::CPPTYPE_MESSAGE:
      break;  // resolve() never targets a block
  }
  return std::nullopt;
}

void set_scalar(pb::Message& message, const pb::FieldDescriptor& field, const Scalar& value) {
  const pb::Reflection& r = *message.GetReflection();
  switch (field.cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_INT32:
      return r.SetInt32(&message, &field, static_cast<std::int32_t>(std::get<std::int64_t>(value)));
    case pb::FieldDescriptor::CPPTYPE_INT64:
      return r.SetInt64(&message, &field, std::get<std::int64_t>(value));
    case pb::FieldDescriptor::CPPTYPE_UINT32:
      return r.SetUInt32(&message, &field, static_cast<std::uint32_t>(std::get<std::uint64_t>(value)));
    case pb::FieldDescriptor::CPPTYPE_UINT64:
      return r.SetUInt64(&message, &field, std::get<std::uint64_t>(value));
    case pb::FieldDescriptor::CPPTYPE_DOUBLE:
      return r.SetDouble(&message, &field, std::get<double>(value));
    case pb::FieldDescriptor::CPPTYPE_FLOAT:
      return r.SetFloat(&message, &field, static_cast<float>(std::get<double>(value)));
    case pb::FieldDescriptor::CPPTYPE_BOOL:
      return r.SetBool(&message, &field, std::get<bool>(value));
    case pb::FieldDescriptor::CPPTYPE_ENUM:
      return r.SetEnum(&message, &field, std::get<const pb::EnumValueDescriptor*>(value));
    case pb::FieldDescriptor::CPPTYPE_STRING:
      return r.SetString(&message, &field, std::get<std::string>(value));
    case pb::FieldDescriptor::CPPTYPE_MESSAGE:
      return;
  }
}

struct Step {
  const pb::FieldDescriptor* field;
  int column;
};

// Maps the path to fields using descriptors only, so a bad override changes nothing.
std::optional<std::vector<Step>> resolve(const pb::Descriptor& root, const std::vector<Part>& parts,
                                         Diagnostic& error) {
  std::vector<Step> steps;
  const pb::Descriptor* type = &root;
  std::string walked;  // the path so far, for messages
  for (const Part& part : parts) {
    error.column = part.column;
    const std::string name(part.text);
    const std::string path = walked.empty() ? name : walked + "." + name;
    if (type == nullptr) {
      error.message = "\"" + walked + "\" is a " + steps.back().field->type_name() +
                      ", not a block; it has no field \"" + name + "\"";
      return std::nullopt;
    }
    const pb::FieldDescriptor* field = type->FindFieldByName(name);
    if (field == nullptr) {
      std::vector<std::string> names;
      for (int i = 0; i < type->field_count(); ++i) names.push_back(type->field(i)->name());
      const std::string nearest = nearest_name(name, names);
      const std::string prefix = walked.empty() ? "" : walked + ".";
      error.message = name.empty() ? "empty field name" : "unknown field \"" + path + "\"";
      error.message += nearest.empty() || name.empty()
                           ? "; valid names: " + join(names, ", ")
                           : " (did you mean \"" + prefix + nearest + "\"?)";
      return std::nullopt;
    }
    if (field->is_repeated()) {
      error.message = "\"" + path + "\" is a repeated field; --set sets single values only";
      return std::nullopt;
    }
    steps.push_back({field, part.column});
    type = field->message_type();
    walked = path;
  }
  if (type != nullptr) {
    error.column = steps.back().column;
    error.message = "\"" + walked + "\" is a block; --set sets single values such as \"" + walked +
                    "." + (type->field_count() > 0 ? type->field(0)->name() : "...") + "\"";
    return std::nullopt;
  }
  return steps;
}

// Applies one override; returns false with `error` filled when it is refused.
bool apply_one(std::string_view text, int index, pb::Message& root, OverrideSites& sites,
               Diagnostic& error) {
  error = {"--set", index, 1, ""};
  const std::size_t equals = text.find('=');
  if (equals == std::string_view::npos) {
    error.message = "expected dotted.path=value, e.g. time.end_time_s=2; got \"" + std::string(text) + "\"";
    return false;
  }
  const Part path = trimmed({text.substr(0, equals), 1});
  const Part value = trimmed({text.substr(equals + 1), static_cast<int>(equals) + 2});
  const auto steps = resolve(*root.GetDescriptor(), split_path(path), error);
  if (!steps) return false;

  const pb::FieldDescriptor& target = *steps->back().field;
  const auto scalar = parse_scalar(target, value.text, error.message);
  if (!scalar) {
    error.column = value.column;
    error.message = std::string(path.text) + ": " + error.message;
    return false;
  }
  pb::Message* message = &root;
  for (std::size_t i = 0; i + 1 < steps->size(); ++i) {
    const Step& step = (*steps)[i];
    const pb::Reflection& r = *message->GetReflection();
    const bool created = !r.HasField(*message, step.field);
    pb::Message* child = r.MutableMessage(message, step.field);
    if (created) sites[{message, step.field}] = {"--set", index, step.column};
    message = child;
  }
  set_scalar(*message, target, *scalar);
  sites[{message, &target}] = {"--set", index, value.column};
  return true;
}

}  // namespace

std::vector<Diagnostic> apply_overrides(const std::vector<std::string>& overrides, pb::Message& root,
                                        OverrideSites& sites) {
  std::vector<Diagnostic> errors;
  for (std::size_t k = 0; k < overrides.size(); ++k) {
    Diagnostic error;
    if (!apply_one(overrides[k], static_cast<int>(k) + 1, root, sites, error))
      errors.push_back(std::move(error));
  }
  return errors;
}

}  // namespace rockcut::scene
