// Independent read-back helpers for the run.h5 tests: plain HDF5 C API, no RunFile code paths
// except the RAII handle. Declared where used (this folder holds .cpp files only).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/h5_handle.hpp"

namespace rockcut::coupler::testing {

std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::path(ROCKCUT_TEST_TMP) / "output" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

h5::Handle open_read_only(const std::filesystem::path& file) {
  return h5::file(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), file.string(),
                  "cannot open read-only");
}

std::vector<hsize_t> dataset_dims(hid_t file, const std::string& path) {
  h5::Handle dset = h5::dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), path, "cannot open");
  h5::Handle space = h5::dataspace(H5Dget_space(dset.get()), path, "no dataspace");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw std::runtime_error(path + ": bad rank");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

template <typename T>
static std::vector<T> read_all(hid_t file, const std::string& path, hid_t mem_type) {
  std::size_t total = 1;
  for (const hsize_t d : dataset_dims(file, path)) total *= static_cast<std::size_t>(d);
  std::vector<T> values(total);
  h5::Handle dset = h5::dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), path, "cannot open");
  if (total > 0) {
    h5::check(H5Dread(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), path,
              "cannot read");
  }
  return values;
}

std::vector<double> read_doubles(hid_t file, const std::string& path) {
  return read_all<double>(file, path, H5T_NATIVE_DOUBLE);
}

std::vector<std::uint64_t> read_u64s(hid_t file, const std::string& path) {
  return read_all<std::uint64_t>(file, path, H5T_NATIVE_UINT64);
}

std::vector<std::int32_t> read_i32s(hid_t file, const std::string& path) {
  return read_all<std::int32_t>(file, path, H5T_NATIVE_INT32);
}

std::string read_string_attribute(hid_t loc, const std::string& name) {
  h5::Handle attr = h5::attribute(H5Aopen(loc, name.c_str(), H5P_DEFAULT), name, "cannot open");
  h5::Handle file_type = h5::datatype(H5Aget_type(attr.get()), name, "no type");
  if (H5Tget_class(file_type.get()) != H5T_STRING) throw std::runtime_error(name + ": not a string");
  if (H5Tis_variable_str(file_type.get()) <= 0) throw std::runtime_error(name + ": not VL");
  if (H5Tget_cset(file_type.get()) != H5T_CSET_UTF8) throw std::runtime_error(name + ": not UTF-8");
  h5::Handle mem_type = h5::utf8_string_type(name);
  char* data = nullptr;
  h5::check(H5Aread(attr.get(), mem_type.get(), &data), name, "cannot read");
  std::string value = data != nullptr ? data : "";
  H5free_memory(data);
  return value;
}

double read_double_attribute(hid_t loc, const std::string& name) {
  h5::Handle attr = h5::attribute(H5Aopen(loc, name.c_str(), H5P_DEFAULT), name, "cannot open");
  double value = 0.0;
  h5::check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &value), name, "cannot read");
  return value;
}

std::uint64_t read_u64_attribute(hid_t loc, const std::string& name) {
  h5::Handle attr = h5::attribute(H5Aopen(loc, name.c_str(), H5P_DEFAULT), name, "cannot open");
  h5::Handle type = h5::datatype(H5Aget_type(attr.get()), name, "no type");
  if (H5Tget_class(type.get()) != H5T_INTEGER || H5Tget_size(type.get()) != 8 ||
      H5Tget_sign(type.get()) != H5T_SGN_NONE) {
    throw std::runtime_error(name + ": not uint64");
  }
  std::uint64_t value = 0;
  h5::check(H5Aread(attr.get(), H5T_NATIVE_UINT64, &value), name, "cannot read");
  return value;
}

std::vector<std::string> attribute_names(hid_t loc) {
  std::vector<std::string> names;
  hsize_t index = 0;
  auto collect = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->push_back(name);
    return 0;
  };
  h5::check(H5Aiterate2(loc, H5_INDEX_NAME, H5_ITER_INC, &index, collect, &names), "attributes",
            "cannot iterate");
  return names;
}

}  // namespace rockcut::coupler::testing
