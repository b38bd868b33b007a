// The reader side of summary.json, for the tests: a strict parser for one flat JSON object.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "output/summary_json.hpp"

namespace rockcut::coupler {

/// Parses `{ "key": value, ... }` where each value is a string, number, true, false or null.
/// Numbers with '.', 'e' or 'E' become double, other numbers int64; null becomes NaN (what a
/// non-finite double was written as). Duplicate keys are returned in order (the caller decides).
/// Throws std::runtime_error "<source>: line L, column C: <problem>" on malformed input,
/// including nested objects or arrays.
std::vector<std::pair<std::string, SummaryValue>> parse_flat_json_object(
    std::string_view text, const std::string& source);

/// Reads a flat JSON object written by Summary::write() (numbers with '.', 'e' or 'null' become
/// double, other integers int64). Throws std::runtime_error on malformed input.
Summary read_summary(const std::filesystem::path& file);

}  // namespace rockcut::coupler
