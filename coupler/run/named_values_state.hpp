// Named values (a step report's scalars) in a checkpoint: the names as one text, the values as one
// array in the same order.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "run/text_lines.hpp"
#include "wire/state_archive.hpp"

namespace rockcut::coupler {

inline void save_named_values(state::StateArchive& a, const std::string& key,
                              const std::vector<std::pair<std::string, double>>& values) {
  std::vector<std::string> names;
  std::vector<double> numbers;
  for (const auto& [name, value] : values) {
    names.push_back(name);
    numbers.push_back(value);
  }
  a.put_text(key, join_lines(names));
  a.put(key, std::move(numbers));
}

inline std::vector<std::pair<std::string, double>> load_named_values(const state::StateArchive& a,
                                                                     const std::string& key) {
  std::vector<std::pair<std::string, double>> out;
  for (std::string& name : split_lines(a.text(key))) out.emplace_back(std::move(name), 0.0);
  const auto numbers = a.values(key, out.size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k].second = numbers[k];
  return out;
}

}  // namespace rockcut::coupler
