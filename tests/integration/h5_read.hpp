// Reading run.h5 from tests with the HDF5 C API (read-only, no writer code involved).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rockcut::test {

class H5Reader {
 public:
  /// Opens read-only; throws std::runtime_error if the file is not a readable HDF5 file.
  explicit H5Reader(const std::filesystem::path& file);
  ~H5Reader();
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  /// All values of a float64 dataset, flattened.
  std::vector<double> doubles(const std::string& path) const;
  /// Names of the members of a group.
  std::vector<std::string> members(const std::string& group) const;
  /// A string attribute of the root group.
  std::string root_attribute(const std::string& name) const;

 private:
  long long file_;
};

/// The path of the last group under /frames ("/frames/NNNNNN"); throws if there is none.
std::string last_frame(const H5Reader& h5);

}  // namespace rockcut::test
