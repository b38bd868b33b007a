#include "output/h5_handle.hpp"

#include <cstring>
#include <stdexcept>
#include <vector>

namespace rockcut::coupler::h5 {

void keep_library_out_of_exit() { H5dont_atexit(); }

void silence_auto_errors() {
  // Errors still land on the stack; take_error_stack() folds them into our exception text.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

namespace {

herr_t collect_error(unsigned /*n*/, const H5E_error2_t* err, void* client) {
  auto* entries = static_cast<std::vector<std::string>*>(client);
  std::string entry;
  if (err->func_name != nullptr) entry.append(err->func_name).append("(): ");
  if (err->desc != nullptr) entry.append(err->desc);
  entries->push_back(std::move(entry));
  return 0;
}

}  // namespace

std::string take_error_stack() {
  std::vector<std::string> entries;  // innermost (the root cause) first, the API call last
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, collect_error, &entries);
  H5Eclear2(H5E_DEFAULT);
  if (entries.empty()) return {};
  // The API-level entry says what was attempted, the innermost one why it failed.
  std::string text = entries.back();
  if (entries.size() > 1) text += " <- " + entries.front();
  return text;
}

void fail(const std::string& context, const std::string& what) {
  std::string message = context + ": " + what;
  const std::string stack = take_error_stack();
  if (!stack.empty()) message += " (HDF5: " + stack + ")";
  throw std::runtime_error(message);
}

Handle utf8_string_type(const std::string& ctx) {
  Handle type = datatype(H5Tcopy(H5T_C_S1), ctx, "cannot copy the string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), ctx, "cannot make a variable-length string type");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), ctx, "cannot set the UTF-8 character set");
  return type;
}

namespace {

/// Deletes `name` on `loc` if present so the caller can create it afresh (type may change).
void remove_attribute_if_present(hid_t loc, const std::string& name, const std::string& ctx) {
  const htri_t exists = H5Aexists(loc, name.c_str());
  check(exists, ctx, "cannot query attribute '" + name + "'");
  if (exists > 0) check(H5Adelete(loc, name.c_str()), ctx, "cannot delete attribute '" + name + "'");
}

}  // namespace

void write_string_attribute(hid_t loc, const std::string& name, const std::string& value,
                            const std::string& ctx) {
  if (name.empty()) throw std::invalid_argument(ctx + ": attribute name is empty");
  if (std::memchr(value.data(), '\0', value.size()) != nullptr) {
    // VL strings are NUL-terminated: the value would be silently truncated.
    throw std::invalid_argument(ctx + ": attribute '" + name + "' contains a NUL character");
  }
  remove_attribute_if_present(loc, name, ctx);
  Handle type = utf8_string_type(ctx);
  Handle space = dataspace(H5Screate(H5S_SCALAR), ctx, "cannot create a scalar dataspace");
  Handle attr = attribute(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT,
                                     H5P_DEFAULT),
                          ctx, "cannot create attribute '" + name + "'");
  const char* data = value.c_str();
  check(H5Awrite(attr.get(), type.get(), &data), ctx, "cannot write attribute '" + name + "'");
  check(attr.close(), ctx, "cannot close attribute '" + name + "'");
}

void write_scalar_attribute(hid_t loc, const std::string& name, hid_t mem_type, hid_t file_type,
                            const void* value, const std::string& ctx) {
  remove_attribute_if_present(loc, name, ctx);
  Handle space = dataspace(H5Screate(H5S_SCALAR), ctx, "cannot create a scalar dataspace");
  Handle attr = attribute(
      H5Acreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), ctx,
      "cannot create attribute '" + name + "'");
  check(H5Awrite(attr.get(), mem_type, value), ctx, "cannot write attribute '" + name + "'");
  check(attr.close(), ctx, "cannot close attribute '" + name + "'");
}

std::string read_string_attribute(hid_t loc, const std::string& name, const std::string& ctx) {
  Handle attr = attribute(H5Aopen(loc, name.c_str(), H5P_DEFAULT), ctx,
                          "cannot open attribute '" + name + "'");
  Handle file_type = datatype(H5Aget_type(attr.get()), ctx, "cannot get the type of '" + name + "'");
  if (H5Tget_class(file_type.get()) != H5T_STRING) {
    fail(ctx, "attribute '" + name + "' is not a string");
  }
  if (H5Tis_variable_str(file_type.get()) > 0) {
    Handle type = utf8_string_type(ctx);
    char* data = nullptr;
    check(H5Aread(attr.get(), type.get(), &data), ctx, "cannot read attribute '" + name + "'");
    std::string value = data ? data : "";
    Handle space = dataspace(H5Aget_space(attr.get()), ctx, "cannot get a dataspace");
    H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, &data);
    return value;
  }
  const std::size_t size = H5Tget_size(file_type.get());
  std::string value(size, '\0');
  check(H5Aread(attr.get(), file_type.get(), value.data()), ctx,
        "cannot read attribute '" + name + "'");
  value.resize(std::strlen(value.c_str()));
  return value;
}

void read_scalar_attribute(hid_t loc, const std::string& name, hid_t mem_type, void* value,
                           const std::string& ctx) {
  Handle attr = attribute(H5Aopen(loc, name.c_str(), H5P_DEFAULT), ctx,
                          "cannot open attribute '" + name + "'");
  check(H5Aread(attr.get(), mem_type, value), ctx, "cannot read attribute '" + name + "'");
}

}  // namespace rockcut::coupler::h5
