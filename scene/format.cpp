#include "scene/format.hpp"

#include <charconv>

#include "rockcut/options.pb.h"

namespace rockcut::scene {

std::string format_double(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string join(const std::vector<std::string>& parts, std::string_view separator) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) out += separator;
    out += parts[i];
  }
  return out;
}

std::vector<std::string> split_choices(std::string_view choices) {
  std::vector<std::string> values;
  while (!choices.empty()) {
    const std::size_t comma = choices.find(',');
    std::string_view value = choices.substr(0, comma);
    while (!value.empty() && value.front() == ' ') value.remove_prefix(1);
    while (!value.empty() && value.back() == ' ') value.remove_suffix(1);
    if (!value.empty()) values.emplace_back(value);
    choices = comma == std::string_view::npos ? std::string_view() : choices.substr(comma + 1);
  }
  return values;
}

std::string bounds_text(const google::protobuf::FieldOptions& options) {
  std::vector<std::string> parts;
  if (options.HasExtension(rockcut::greater_than))
    parts.push_back("> " + format_double(options.GetExtension(rockcut::greater_than)));
  if (options.HasExtension(rockcut::min))
    parts.push_back(">= " + format_double(options.GetExtension(rockcut::min)));
  if (options.HasExtension(rockcut::max))
    parts.push_back("<= " + format_double(options.GetExtension(rockcut::max)));
  return join(parts, " and ");
}

std::string unit_suffix(const google::protobuf::FieldOptions& options) {
  return options.HasExtension(rockcut::unit) ? " [" + options.GetExtension(rockcut::unit) + "]" : "";
}

}  // namespace rockcut::scene
