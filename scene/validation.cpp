#include "scene/validation.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

#include "rockcut/options.pb.h"
#include "scene/field_docs.hpp"
#include "scene/format.hpp"
#include "scene/nearest_name.hpp"
#include "scene/particle_budget.hpp"

#include <stdexcept>

namespace rockcut::scene {
namespace {

namespace pb = google::protobuf;
using Field = pb::FieldDescriptor;

struct Number {
  double value;
  std::string text;  // as the user would write it
};

template <class T>
T get(const pb::Message& m, const Field& f, int index,
      T (pb::Reflection::*single)(const pb::Message&, const Field*) const,
      T (pb::Reflection::*repeated)(const pb::Message&, const Field*, int) const) {
  const pb::Reflection& r = *m.GetReflection();
  return f.is_repeated() ? (r.*repeated)(m, &f, index) : (r.*single)(m, &f);
}

template <class T>
Number integer(T value) {
  return {static_cast<double>(value), std::to_string(value)};
}

// The value of a numeric field (element `index` of a repeated one); nullopt for other types.
std::optional<Number> number_of(const pb::Message& m, const Field& f, int index) {
  using R = pb::Reflection;
  switch (f.cpp_type()) {
    case Field::CPPTYPE_INT32:
      return integer(get(m, f, index, &R::GetInt32, &R::GetRepeatedInt32));
    case Field::CPPTYPE_INT64:
      return integer(get(m, f, index, &R::GetInt64, &R::GetRepeatedInt64));
    case Field::CPPTYPE_UINT32:
      return integer(get(m, f, index, &R::GetUInt32, &R::GetRepeatedUInt32));
    case Field::CPPTYPE_UINT64:
      return integer(get(m, f, index, &R::GetUInt64, &R::GetRepeatedUInt64));
    case Field::CPPTYPE_DOUBLE: {
      const double value = get(m, f, index, &R::GetDouble, &R::GetRepeatedDouble);
      return Number{value, format_double(value)};
    }
    case Field::CPPTYPE_FLOAT: {
      const double value = get(m, f, index, &R::GetFloat, &R::GetRepeatedFloat);
      return Number{value, format_double(value)};
    }
    default:
      return std::nullopt;
  }
}

bool in_bounds(double value, const pb::FieldOptions& options) {
  return !(options.HasExtension(rockcut::greater_than) && !(value > options.GetExtension(rockcut::greater_than))) &&
         !(options.HasExtension(rockcut::min) && !(value >= options.GetExtension(rockcut::min))) &&
         !(options.HasExtension(rockcut::max) && !(value <= options.GetExtension(rockcut::max)));
}

class Validator {
 public:
  explicit Validator(const OverrideSites& sites) : sites_(sites) {}

  // `opening` is where the message starts: missing fields are reported there.
  void check_message(const pb::Message& message, const std::string& path, const SourceMap* map,
                     const Location& opening) {
    const pb::Descriptor& type = *message.GetDescriptor();
    const pb::Reflection& r = *message.GetReflection();
    for (int i = 0; i < type.field_count(); ++i) {
      const Field& field = *type.field(i);
      const std::string field_path = path.empty() ? field.name() : path + "." + field.name();
      const int count = field.is_repeated() ? r.FieldSize(message, &field)
                                            : (r.HasField(message, &field) ? 1 : 0);
      if (count == 0 && field.options().GetExtension(rockcut::required)) {
        const std::string_view doc = field_doc(field.full_name());
        report(opening, "missing required field \"" + field_path + "\"" +
                            unit_suffix(field.options()) + (doc.empty() ? "" : ": ") + std::string(doc));
      }
      if (field.is_repeated() && count > 1) check_unique(message, field, field_path, map, opening);
      for (int k = 0; k < count; ++k) {
        const int index = field.is_repeated() ? k : -1;
        const std::string value_path =
            field.is_repeated() ? field_path + "[" + std::to_string(k) + "]" : field_path;
        const Location at = where(message, field, index, map, opening);
        if (field.cpp_type() == Field::CPPTYPE_MESSAGE) {
          const pb::Message& child = field.is_repeated() ? r.GetRepeatedMessage(message, &field, k)
                                                         : r.GetMessage(message, &field);
          check_message(child, value_path, map ? map->child(&field, index) : nullptr, at);
        } else {
          check_value(message, field, index, value_path, at);
        }
      }
    }
  }

  // Checks that need more than one field (scene/particle_budget.hpp).
  void check_scene(const rockcut::Scene& scene, const SourceMap* map, const Location& opening) {
    if (const auto problem = particle_budget_problem(scene)) {
      const Field* dem = scene.GetDescriptor()->FindFieldByName("dem");
      report(where(scene, *dem, -1, map, opening), *problem);
    }
  }

  std::vector<Diagnostic> diagnostics;

 private:
  // A list must not name a thing twice: two walls or pressure nodes of one name would write one
  // time-series column, a frame field listed twice one dataset.
  void check_unique(const pb::Message& message, const Field& field, const std::string& path,
                    const SourceMap* map, const Location& opening) {
    const pb::Reflection& r = *message.GetReflection();
    const Field* name = field.message_type() ? field.message_type()->FindFieldByName("name") : nullptr;
    if (field.cpp_type() == Field::CPPTYPE_MESSAGE && (!name || name->type() != Field::TYPE_STRING)) return;
    if (field.cpp_type() != Field::CPPTYPE_MESSAGE && field.cpp_type() != Field::CPPTYPE_STRING) return;
    std::vector<std::string> seen;
    for (int k = 0; k < r.FieldSize(message, &field); ++k) {
      const std::string value = field.cpp_type() == Field::CPPTYPE_MESSAGE
                                    ? r.GetRepeatedMessage(message, &field, k).GetReflection()->GetString(
                                          r.GetRepeatedMessage(message, &field, k), name)
                                    : r.GetRepeatedString(message, &field, k);
      if (std::find(seen.begin(), seen.end(), value) != seen.end()) {
        report(where(message, field, k, map, opening),
               path + "[" + std::to_string(k) + "]" + (name ? ".name" : "") + " = \"" + value +
                   "\" is given twice; each must be different");
      }
      seen.push_back(value);
    }
  }

  void check_value(const pb::Message& message, const Field& field, int index, const std::string& path,
                   const Location& at) {
    const pb::FieldOptions& options = field.options();
    if (const auto number = number_of(message, field, index)) {
      if (!std::isfinite(number->value))
        report(at, path + " = " + number->text + " is not a finite number");
      else if (!in_bounds(number->value, options))
        report(at, path + " = " + number->text + " is out of range: must be " + bounds_text(options) +
                       unit_suffix(options));
    }
    if (field.cpp_type() == Field::CPPTYPE_STRING && field.name() == "name") {
      // Names become HDF5 datasets and time-series columns (wall_<name>_force_x_n_per_m).
      const pb::Reflection& r = *message.GetReflection();
      const std::string value = field.is_repeated() ? r.GetRepeatedString(message, &field, index)
                                                    : r.GetString(message, &field);
      const bool plain = !value.empty() && value.size() <= 64 &&
                         std::all_of(value.begin(), value.end(), [](char c) {
                           return std::isalnum(static_cast<unsigned char>(c)) || c == '_' ||
                                  c == '-' || c == '.';
                         }) && value != "." && value != "..";
      if (!plain) {
        report(at, path + " is not a plain name: use 1-64 letters, digits, '_', '-' or '.'");
      }
    }
    if (field.cpp_type() == Field::CPPTYPE_STRING && options.HasExtension(rockcut::choices)) {
      const pb::Reflection& r = *message.GetReflection();
      const std::string value = field.is_repeated() ? r.GetRepeatedString(message, &field, index)
                                                    : r.GetString(message, &field);
      const std::vector<std::string> allowed = split_choices(options.GetExtension(rockcut::choices));
      if (std::find(allowed.begin(), allowed.end(), value) == allowed.end())
        report(at, path + " = \"" + value + "\" is not allowed; choose one of: " + join(allowed, ", ") +
                       did_you_mean(value, allowed));
    }
  }

  // Where a field's value was written: the override that set it, else its place in the file (or
  // the base) that wrote it, else (a field the map does not know) the start of its message.
  Location where(const pb::Message& message, const Field& field, int index, const SourceMap* map,
                 const Location& opening) const {
    if (const auto site = sites_.find({&message, &field}); site != sites_.end()) return site->second;
    const Location* written = map ? map->find(&field, index) : nullptr;
    return written ? *written : opening;
  }

  void report(const Location& at, std::string message) {
    diagnostics.push_back({at.file, at.line, at.column, std::move(message)});
  }

  const OverrideSites& sites_;
};

}  // namespace

std::vector<Diagnostic> validate(const pb::Message& root, const std::string& file, const SourceMap* map,
                                 const OverrideSites& sites) {
  Validator validator(sites);
  validator.check_message(root, "", map, {file, 1, 1});
  if (const auto* scene = dynamic_cast<const rockcut::Scene*>(&root)) {
    validator.check_scene(*scene, map, {file, 1, 1});
  }
  return std::move(validator.diagnostics);
}

namespace {

void throw_if_any(const std::vector<Diagnostic>& problems, const std::string& part) {
  if (problems.empty()) return;
  std::string text = "the " + part + " sent in Init is not valid:";
  constexpr std::size_t kShown = 5;
  for (std::size_t k = 0; k < problems.size() && k < kShown; ++k) {
    text += " " + problems[k].message + (k + 1 < problems.size() ? ";" : "");
  }
  if (problems.size() > kShown) text += " and " + std::to_string(problems.size() - kShown) + " more";
  throw std::invalid_argument(text);
}

}  // namespace

void validate_received(const rockcut::wire::DemConfig& config) {
  std::vector<Diagnostic> problems = validate(config, "Init", nullptr, {});
  if (const auto problem = particle_budget_problem(config.dem())) {
    problems.push_back({"Init", 1, 1, *problem});
  }
  throw_if_any(problems, "DEM part of the scene");
}

void validate_received(const rockcut::wire::FluidConfig& config) {
  throw_if_any(validate(config, "Init", nullptr, {}), "fluid part of the scene");
}

}  // namespace rockcut::scene
