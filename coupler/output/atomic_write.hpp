// Replace a small text file so readers see either the old or the new content, never a torn one.
#pragma once

#include <filesystem>
#include <string_view>

namespace rockcut::coupler {

/// Writes `content` to a temporary file beside `target`, fsyncs it and renames it over `target`.
/// Throws std::runtime_error (naming the file) on failure; the temporary file is removed then.
void write_file_atomically(const std::filesystem::path& target, std::string_view content);

}  // namespace rockcut::coupler
