// Lists of names stored as one text, a name per line ("a\nb\n"), as checkpoints keep them.
#pragma once

#include <string>
#include <vector>

namespace rockcut::coupler {

inline std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

/// The lines of `text`; a last line without its newline counts too.
inline std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    out.push_back(text.substr(start, end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace rockcut::coupler
