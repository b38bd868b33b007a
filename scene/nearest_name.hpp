// "Did you mean ...?" for misspelled field names, enum values and choices.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rockcut::scene {

/// Edit distance (insertions, deletions, substitutions and swaps of neighbours), ignoring case.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate nearest to `word`, or "" when none is within max(2, length / 3) edits.
std::string nearest_name(std::string_view word, const std::vector<std::string>& candidates);

/// ` (did you mean "X"?)` with the nearest candidate, or "" when none is close.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

/// did_you_mean(), or `; valid names: a, b, c` when nothing is close, so the user always gets a lead.
std::string name_hint(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace rockcut::scene
