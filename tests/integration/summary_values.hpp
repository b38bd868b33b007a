// Reading values back from a run's summary.json and comparing arrays, for integration tests.
#pragma once

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/summary_json.hpp"

namespace rockcut::test {

/// A numeric value (double or integer); throws naming the key if it is missing or not a number.
inline double number(const coupler::Summary& s, const std::string& key) {
  const auto v = s.get(key);
  if (!v) throw std::runtime_error("summary.json lacks " + key);
  if (auto d = std::get_if<double>(&*v)) return *d;
  if (auto i = std::get_if<std::int64_t>(&*v)) return static_cast<double>(*i);
  throw std::runtime_error(key + " is not a number");
}

/// A string value, or "" if it is missing or not a string.
inline std::string text(const coupler::Summary& s, const std::string& key) {
  const auto v = s.get(key);
  if (!v || !std::holds_alternative<std::string>(*v)) return "";
  return std::get<std::string>(*v);
}

inline bool bit_identical(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace rockcut::test
