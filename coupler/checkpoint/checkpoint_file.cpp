#include "checkpoint/checkpoint_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "output/h5_handle.hpp"
#include "run/text_lines.hpp"

namespace rockcut::coupler {

namespace {

namespace fs = std::filesystem;

constexpr const char* kFormat = "rockcut checkpoint";
constexpr const char* kFormatVersion = "1";
constexpr const char* kPrefix = "checkpoint_";
constexpr const char* kSuffix = ".h5";
constexpr const char* kTextPrefix = "text:";
const char* const kParts[] = {"coupler", "dem", "fluid"};

struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) {
      h ^= p[k];
      h *= 1099511628211ull;
    }
  }
  void text(const std::string& s) {
    const std::uint64_t n = s.size();
    bytes(&n, sizeof n);
    bytes(s.data(), s.size());
  }
};

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}



void fsync_path(const fs::path& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? (O_RDONLY | O_DIRECTORY) : O_RDONLY);
  if (fd < 0) throw std::runtime_error(path.string() + ": cannot open to sync: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) throw std::runtime_error(path.string() + ": fsync failed: " + std::strerror(err));
}

void write_part(hid_t file, const std::string& name, const state::StateArchive& part,
                const std::string& ctx) {
  h5::Handle group = h5::group(H5Gcreate2(file, ("/" + name).c_str(), H5P_DEFAULT, H5P_DEFAULT,
                                          H5P_DEFAULT),
                               ctx, "cannot create group /" + name);
  for (const auto& [key, text] : part.texts()) {
    h5::write_string_attribute(group.get(), kTextPrefix + key, text, ctx + ": /" + name);
  }
  for (const state::StateArray& a : part.arrays()) {
    const std::string where = "/" + name + "/" + a.name;
    const hsize_t dims = a.values.size();
    h5::Handle space = h5::dataspace(H5Screate_simple(1, &dims, nullptr), ctx,
                                     "cannot create the dataspace of " + where);
    h5::Handle set = h5::dataset(H5Dcreate2(group.get(), a.name.c_str(), H5T_IEEE_F64LE,
                                            space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                 ctx, "cannot create " + where);
    if (dims > 0) {
      h5::check(H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                         a.values.data()),
                ctx, "cannot write " + where);
    }
    const std::uint32_t components = a.components;
    h5::write_scalar_attribute(set.get(), "components", H5T_NATIVE_UINT32, H5T_STD_U32LE,
                               &components, ctx + ": " + where);
  }
}

herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

herr_t collect_attribute(hid_t, const char* name, const H5A_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

state::StateArchive read_part(hid_t file, const std::string& name, const std::string& ctx) {
  state::StateArchive part;
  h5::Handle group = h5::group(H5Gopen2(file, ("/" + name).c_str(), H5P_DEFAULT), ctx,
                               "no group /" + name);
  std::vector<std::string> attributes;
  hsize_t index = 0;
  h5::check(H5Aiterate2(group.get(), H5_INDEX_NAME, H5_ITER_INC, &index, collect_attribute,
                        &attributes),
            ctx, "cannot list the attributes of /" + name);
  for (const std::string& a : attributes) {
    if (a.rfind(kTextPrefix, 0) != 0) continue;
    part.put_text(a.substr(std::strlen(kTextPrefix)),
                  h5::read_string_attribute(group.get(), a, ctx + ": /" + name));
  }
  std::vector<std::string> names;
  index = 0;
  h5::check(H5Literate(group.get(), H5_INDEX_NAME, H5_ITER_INC, &index, collect_name, &names),
            ctx, "cannot list /" + name);
  for (const std::string& n : names) {
    const std::string where = "/" + name + "/" + n;
    h5::Handle set = h5::dataset(H5Dopen2(group.get(), n.c_str(), H5P_DEFAULT), ctx,
                                 "cannot open " + where);
    h5::Handle space = h5::dataspace(H5Dget_space(set.get()), ctx, "no dataspace for " + where);
    if (H5Sget_simple_extent_ndims(space.get()) != 1) h5::fail(ctx, where + " is not 1-D");
    hsize_t dims = 0;
    H5Sget_simple_extent_dims(space.get(), &dims, nullptr);
    std::vector<double> values(dims);
    if (dims > 0) {
      h5::check(H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                        values.data()),
                ctx, "cannot read " + where);
    }
    std::uint32_t components = 1;
    h5::read_scalar_attribute(set.get(), "components", H5T_NATIVE_UINT32, &components,
                              ctx + ": " + where);
    if (components == 0 || values.size() % components != 0) {
      throw CheckpointError(where + " has " + std::to_string(values.size()) +
                            " values, not a multiple of its " + std::to_string(components) +
                            " components");
    }
    part.put(n, std::move(values), components);
  }
  return part;
}

}  // namespace

std::string checkpoint_file_name(std::uint64_t step) {
  char name[64];
  std::snprintf(name, sizeof name, "%s%012llu%s", kPrefix, static_cast<unsigned long long>(step),
                kSuffix);
  return name;
}

std::uint64_t checkpoint_checksum(const Checkpoint& c) {
  Fnv1a f;
  f.text(c.rockcut_version);
  f.bytes(&c.protocol_version, sizeof c.protocol_version);
  f.text(c.scene_text);
  f.text(c.scene_path);
  f.text(join_lines(c.overrides));
  f.bytes(&c.step, sizeof c.step);
  f.bytes(&c.time_s, sizeof c.time_s);
  for (const auto& [name, part] : c.parts) {
    f.text(name);
    for (const auto& [key, text] : part.texts()) {
      f.text(key);
      f.text(text);
    }
    std::vector<const state::StateArray*> arrays;
    for (const state::StateArray& a : part.arrays()) arrays.push_back(&a);
    std::sort(arrays.begin(), arrays.end(),
              [](const auto* a, const auto* b) { return a->name < b->name; });
    for (const state::StateArray* a : arrays) {
      f.text(a->name);
      f.bytes(&a->components, sizeof a->components);
      const std::uint64_t n = a->values.size();
      f.bytes(&n, sizeof n);
      f.bytes(a->values.data(), a->values.size() * sizeof(double));
    }
  }
  return f.h;
}

fs::path write_checkpoint(const fs::path& dir, const Checkpoint& c) {
  fs::create_directories(dir);
  // The folder must be this user's own directory, not a link planted in its place (the fresh run
  // removes checkpoints/, and another user could re-create it as a link to somewhere else).
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid()) {
    throw std::runtime_error(dir.string() +
                             ": not a directory of this user's (a symbolic link or another "
                             "user's folder): checkpoints are not written through it");
  }
  const fs::path final_path = dir / checkpoint_file_name(c.step);
  const fs::path temp_path = dir / (std::string(".") + checkpoint_file_name(c.step) + ".tmp");
  const std::string ctx = temp_path.string();
  h5::silence_auto_errors();
  try {
    // A fresh file, never through a link: what lies at the temporary's name is unlinked (a link,
    // not its target) and the file is created exclusively.
    std::error_code unlinked;
    fs::remove(temp_path, unlinked);
    h5::Handle fapl = h5::plist(H5Pcreate(H5P_FILE_ACCESS), ctx, "cannot create access list");
    h5::check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), ctx, "cannot set close degree");
    h5::Handle file = h5::file(H5Fcreate(ctx.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.get()), ctx,
                               "cannot create file");
    const hid_t root = file.get();
    h5::write_string_attribute(root, "format", kFormat, ctx);
    h5::write_string_attribute(root, "format_version", kFormatVersion, ctx);
    h5::write_string_attribute(root, "rockcut_version", c.rockcut_version, ctx);
    h5::write_scalar_attribute(root, "protocol_version", H5T_NATIVE_UINT32, H5T_STD_U32LE,
                               &c.protocol_version, ctx);
    h5::write_string_attribute(root, "scene", c.scene_text, ctx);
    h5::write_string_attribute(root, "scene_path", c.scene_path, ctx);
    h5::write_string_attribute(root, "overrides", join_lines(c.overrides), ctx);
    h5::write_scalar_attribute(root, "step", H5T_NATIVE_UINT64, H5T_STD_U64LE, &c.step, ctx);
    h5::write_scalar_attribute(root, "time_s", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, &c.time_s, ctx);
    for (const auto& [name, part] : c.parts) write_part(root, name, part, ctx);
    h5::write_string_attribute(root, "checksum", hex(checkpoint_checksum(c)), ctx);
    h5::check(H5Fflush(root, H5F_SCOPE_GLOBAL), ctx, "cannot flush");
    if (file.close() < 0) h5::fail(ctx, "cannot close");
    fsync_path(temp_path, false);
    fs::rename(temp_path, final_path);
    fsync_path(dir, true);
  } catch (...) {
    std::error_code ec;
    fs::remove(temp_path, ec);
    throw;
  }
  return final_path;
}

Checkpoint read_checkpoint(const fs::path& path) {
  const std::string ctx = path.string();
  h5::silence_auto_errors();
  if (H5Fis_hdf5(ctx.c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    throw CheckpointError("not a readable HDF5 file (truncated or damaged)");
  }
  Checkpoint c;
  std::string checksum;
  try {
    h5::Handle file = h5::file(H5Fopen(ctx.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), ctx,
                               "cannot open");
    const hid_t root = file.get();
    if (H5Aexists(root, "format") <= 0 || h5::read_string_attribute(root, "format", ctx) != kFormat) {
      throw CheckpointError("not a rockcut checkpoint (no format attribute \"" +
                            std::string(kFormat) + "\")");
    }
    const std::string version = h5::read_string_attribute(root, "format_version", ctx);
    if (version != kFormatVersion) {
      throw CheckpointError("checkpoint format " + version + ", this program reads format " +
                            kFormatVersion);
    }
    c.rockcut_version = h5::read_string_attribute(root, "rockcut_version", ctx);
    h5::read_scalar_attribute(root, "protocol_version", H5T_NATIVE_UINT32, &c.protocol_version, ctx);
    c.scene_text = h5::read_string_attribute(root, "scene", ctx);
    c.scene_path = h5::read_string_attribute(root, "scene_path", ctx);
    c.overrides = split_lines(h5::read_string_attribute(root, "overrides", ctx));
    h5::read_scalar_attribute(root, "step", H5T_NATIVE_UINT64, &c.step, ctx);
    h5::read_scalar_attribute(root, "time_s", H5T_NATIVE_DOUBLE, &c.time_s, ctx);
    for (const char* part : kParts) {
      if (H5Lexists(root, part, H5P_DEFAULT) > 0) c.parts[part] = read_part(root, part, ctx);
    }
    checksum = h5::read_string_attribute(root, "checksum", ctx);
  } catch (const CheckpointError&) {
    throw;
  } catch (const std::exception& e) {
    H5Eclear2(H5E_DEFAULT);
    throw CheckpointError(std::string("unreadable: ") + e.what());
  }
  if (checksum != hex(checkpoint_checksum(c))) {
    throw CheckpointError("checksum mismatch (stored " + checksum + ", contents " +
                          hex(checkpoint_checksum(c)) + "): the file is corrupted");
  }
  return c;
}

std::vector<fs::path> list_checkpoints(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(kPrefix, 0) == 0 && name.size() > std::strlen(kSuffix) &&
        name.compare(name.size() - std::strlen(kSuffix), std::string::npos, kSuffix) == 0) {
      out.push_back(entry.path());
    }
  }
  std::sort(out.begin(), out.end(), [](const fs::path& a, const fs::path& b) {
    return a.filename().string() > b.filename().string();
  });
  return out;
}

void prune_checkpoints(const fs::path& dir, unsigned keep) {
  const std::vector<fs::path> all = list_checkpoints(dir);
  std::error_code ec;
  for (std::size_t k = keep; k < all.size(); ++k) fs::remove(all[k], ec);
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(std::string(".") + kPrefix, 0) == 0 && name.ends_with(".tmp")) {
      fs::remove(entry.path(), ec);
    }
  }
}

}  // namespace rockcut::coupler
