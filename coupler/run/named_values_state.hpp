// Named values (a step report's scalars) in a checkpoint: the names as one text, the values as one
// array in the same order.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "state/state_archive.hpp"

namespace rockcut::coupler {

inline void save_named_values(state::StateArchive& a, const std::string& key,
                              const std::vector<std::pair<std::string, double>>& values) {
  std::string names;
  std::vector<double> numbers;
  for (const auto& [name, value] : values) {
    names += name + "\n";
    numbers.push_back(value);
  }
  a.put_text(key, names);
  a.put(key, std::move(numbers));
}

inline std::vector<std::pair<std::string, double>> load_named_values(const state::StateArchive& a,
                                                                     const std::string& key) {
  const std::string& names = a.text(key);
  std::vector<std::pair<std::string, double>> out;
  std::size_t start = 0;
  while (start < names.size()) {
    const std::size_t end = names.find('\n', start);
    if (end == std::string::npos) break;
    out.emplace_back(names.substr(start, end - start), 0.0);
    start = end + 1;
  }
  const auto numbers = a.values(key, out.size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k].second = numbers[k];
  return out;
}

}  // namespace rockcut::coupler
