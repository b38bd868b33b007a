// Small RAII layer over the HDF5 C API: one owning handle type plus checked call helpers that turn
// a failed H5* call into std::runtime_error naming the file, the object and HDF5's own message.
#pragma once

#include <hdf5.h>

#include <string>
#include <utility>

namespace rockcut::coupler::h5 {

/// Turns off HDF5's automatic printing of its error stack (we report errors ourselves).
void silence_auto_errors();
/// Call first, before any other HDF5 call: HDF5 then does not close files again at exit, which
/// crashes in its library shutdown when a file could not be closed (a full disk, ulimit -f).
void keep_library_out_of_exit();

/// The innermost messages of the current HDF5 error stack ("" if empty); clears the stack.
std::string take_error_stack();

/// Throws std::runtime_error("<context>: <what>: <HDF5 error stack>").
[[noreturn]] void fail(const std::string& context, const std::string& what);

/// Owns one hid_t and closes it with the matching H5*close function. Move-only.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);

  Handle() = default;
  Handle(hid_t id, Closer closer) noexcept : id_(id), closer_(closer) {}
  ~Handle() { (void)close(); }
  Handle(Handle&& other) noexcept
      : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      (void)close();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  hid_t get() const noexcept { return id_; }
  bool valid() const noexcept { return id_ >= 0; }

  /// Closes now; returns the closer's status (0 when there was nothing to close).
  herr_t close() noexcept {
    herr_t status = 0;
    if (id_ >= 0 && closer_ != nullptr) status = closer_(id_);
    id_ = H5I_INVALID_HID;
    return status;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

/// Wraps a freshly returned id, throwing (with context) if the call that produced it failed.
inline Handle checked(hid_t id, Handle::Closer closer, const std::string& context,
                      const std::string& what) {
  if (id < 0) fail(context, what);
  return Handle(id, closer);
}

/// Throws (with context) if an herr_t / htri_t style status is negative.
inline void check(long long status, const std::string& context, const std::string& what) {
  if (status < 0) fail(context, what);
}

// Typed shorthands for the common object kinds.
inline Handle file(hid_t id, const std::string& ctx, const std::string& what) {
  return checked(id, H5Fclose, ctx, what);
}
inline Handle group(hid_t id, const std::string& ctx, const std::string& what) {
  return checked(id, H5Gclose, ctx, what);
}
inline Handle dataset(hid_t id, const std::string& ctx, const std::string& what) {
  return checked(id, H5Dclose, ctx, what);
}
inline Handle dataspace(hid_t id, const std::string& ctx, const std::string& what) {
  return checked(id, H5Sclose, ctx, what);
}
inline Handle datatype(hid_t id, const std::string& ctx, const std::string& what) {
  return checked(id, H5Tclose, ctx, what);
}
inline Handle attribute(hid_t id, const std::string& ctx, const std::string& what) {
  return checked(id, H5Aclose, ctx, what);
}
inline Handle plist(hid_t id, const std::string& ctx, const std::string& what) {
  return checked(id, H5Pclose, ctx, what);
}

/// A variable-length UTF-8 string type (scene text can exceed the 64 KiB limit a fixed-length
/// attribute has in the default object-header format; VL strings live in the global heap).
Handle utf8_string_type(const std::string& ctx);

/// Writes (or overwrites) a scalar VL UTF-8 string attribute on `loc`.
void write_string_attribute(hid_t loc, const std::string& name, const std::string& value,
                            const std::string& ctx);

/// Writes a scalar attribute of a native numeric type (H5T_NATIVE_DOUBLE, H5T_NATIVE_UINT64...).
void write_scalar_attribute(hid_t loc, const std::string& name, hid_t mem_type, hid_t file_type,
                            const void* value, const std::string& ctx);
/// Reads a scalar string attribute (variable or fixed length) of `loc`.
std::string read_string_attribute(hid_t loc, const std::string& name, const std::string& ctx);
/// Reads a scalar numeric attribute of `loc` into `value`, converted to `mem_type`.
void read_scalar_attribute(hid_t loc, const std::string& name, hid_t mem_type, void* value,
                           const std::string& ctx);

}  // namespace rockcut::coupler::h5
