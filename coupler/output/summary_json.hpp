// summary.json: the headline scalars of a run, for scripts and regression tests. (The tests read it
// back with tests/support/summary_parser.hpp.)
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace rockcut::coupler {

using SummaryValue = std::variant<double, std::int64_t, bool, std::string>;

/// An ordered set of key/value pairs written as one flat JSON object.
class Summary {
 public:
  void set(const std::string& key, SummaryValue value);  ///< replaces an existing key in place
  const std::vector<std::pair<std::string, SummaryValue>>& entries() const { return entries_; }
  std::optional<SummaryValue> get(const std::string& key) const;

  /// Writes atomically (to a temporary file, then rename). Non-finite doubles are written as null.
  void write(const std::filesystem::path& file) const;
  std::string to_json() const;

 private:
  std::vector<std::pair<std::string, SummaryValue>> entries_;
};

}  // namespace rockcut::coupler
