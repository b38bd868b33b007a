#include "integration/h5_read.hpp"

#include <algorithm>

#include <hdf5.h>

#include <cstdlib>
#include <stdexcept>

namespace rockcut::test {

H5Reader::H5Reader(const std::filesystem::path& file) {
  // The tests peek at run.h5 while the coupler still writes it; HDF5 1.10 locks a file open for
  // writing unless readers opt out.
  setenv("HDF5_USE_FILE_LOCKING", "FALSE", 1);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  file_ = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_ < 0) throw std::runtime_error("cannot open " + file.string() + " as HDF5");
}

H5Reader::~H5Reader() { H5Fclose(file_); }

std::vector<double> H5Reader::doubles(const std::string& path) const {
  const hid_t ds = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
  if (ds < 0) throw std::runtime_error("no dataset " + path);
  const hid_t space = H5Dget_space(ds);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<double> values(static_cast<std::size_t>(n));
  const herr_t rc = n ? H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data())
                      : 0;
  H5Sclose(space);
  H5Dclose(ds);
  if (rc < 0) throw std::runtime_error("cannot read " + path);
  return values;
}

std::vector<std::string> H5Reader::members(const std::string& group) const {
  std::vector<std::string> names;
  const hid_t g = H5Gopen2(file_, group.c_str(), H5P_DEFAULT);
  if (g < 0) throw std::runtime_error("no group " + group);
  H5G_info_t info;
  H5Gget_info(g, &info);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[256];
    H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name, H5P_DEFAULT);
    names.emplace_back(name);
  }
  H5Gclose(g);
  return names;
}

std::string H5Reader::root_attribute(const std::string& name) const {
  const hid_t attr = H5Aopen(file_, name.c_str(), H5P_DEFAULT);
  if (attr < 0) throw std::runtime_error("no root attribute " + name);
  const hid_t type = H5Aget_type(attr);
  std::string value;
  if (H5Tis_variable_str(type) > 0) {
    char* s = nullptr;
    const hid_t mem = H5Tcopy(H5T_C_S1);
    H5Tset_size(mem, H5T_VARIABLE);
    H5Tset_cset(mem, H5Tget_cset(type));
    H5Aread(attr, mem, &s);
    if (s) value = s;
    H5free_memory(s);
    H5Tclose(mem);
  } else {
    value.resize(H5Tget_size(type));
    H5Aread(attr, type, value.data());
    while (!value.empty() && value.back() == '\0') value.pop_back();
  }
  H5Tclose(type);
  H5Aclose(attr);
  return value;
}

std::string last_frame(const H5Reader& h5) {
  auto frames = h5.members("/frames");
  if (frames.empty()) throw std::runtime_error("run.h5 has no frames");
  return "/frames/" + *std::max_element(frames.begin(), frames.end());
}

}  // namespace rockcut::test
