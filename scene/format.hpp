// Small text helpers shared by the loader and the reference generator.
#pragma once

#include <google/protobuf/descriptor.pb.h>

#include <string>
#include <string_view>
#include <vector>

namespace rockcut::scene {

/// Shortest text that reads back as the same double ("0.2", "1e-12", "2800", "nan").
std::string format_double(double value);

std::string join(const std::vector<std::string>& parts, std::string_view separator);

/// The values of a `(rockcut.choices)` option: "a, b,c" -> {"a", "b", "c"}.
std::vector<std::string> split_choices(std::string_view choices);

/// The bounds a field's options declare, e.g. "> 0 and <= 1"; "" when none.
std::string bounds_text(const google::protobuf::FieldOptions& options);

/// " [unit]" when the options declare a unit, else "".
std::string unit_suffix(const google::protobuf::FieldOptions& options);

}  // namespace rockcut::scene
