#include "output/run_file.hpp"

#include <map>

#include <algorithm>
#include <cstdlib>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "output/frame_writer.hpp"
#include "output/h5_handle.hpp"
#include "output/timeseries.hpp"
#include "output/write_room.hpp"
#include "output/xdmf_writer.hpp"

namespace rockcut::coupler {

namespace {

constexpr const char* kH5Name = "run.h5";
constexpr const char* kXdmfName = "run.xdmf";
constexpr const char* kVertexIds = "/xdmf/vertex_ids";
constexpr hsize_t kVertexIdChunk = 65536;

std::string frame_group_path(std::size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "/frames/%06zu", index);
  return name;
}

}  // namespace

struct RunFile::Impl {
  std::string ctx;  // the HDF5 file's path, prefixed to every error
  h5::Handle file;
  std::optional<Timeseries> timeseries;
  std::map<std::string, Timeseries> tables;  // event logs such as /breaks
  h5::Handle vertex_ids;  // 0, 1, 2, ...: the connectivity every XDMF topology selects from
  hsize_t vertex_id_count = 0;
  std::optional<XdmfWriter> xdmf;
  std::size_t frames = 0;
  bool open = false;

  void require_open() const {
    if (!open) throw std::logic_error(ctx + ": run file is closed");
  }
  void create_vertex_ids();
  void grow_vertex_ids(std::size_t count);
  void flush() {
    h5::check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), ctx, "cannot flush");
  }
  /// Throws, before anything is written, when `more_bytes` would not fit (write_room.hpp).
  void require_room(std::uint64_t more_bytes,
                    std::uint64_t reserve_bytes = kCloseReserveBytes) const {
    hsize_t allocated = 0;
    if (H5Fget_filesize(file.get(), &allocated) < 0) {
      H5Eclear2(H5E_DEFAULT);
      return;  // cannot tell: the write itself reports a failure
    }
    std::error_code ec;
    const std::uintmax_t on_disk = std::filesystem::file_size(ctx, ec);
    if (auto why = lacks_room(ctx, allocated, ec ? allocated : on_disk, more_bytes,
                              reserve_bytes)) {
      throw std::runtime_error(ctx + ": " + *why);
    }
  }
};

void RunFile::Impl::create_vertex_ids() {
  h5::Handle group = h5::group(H5Gcreate2(file.get(), "/xdmf", H5P_DEFAULT, H5P_DEFAULT,
                                          H5P_DEFAULT),
                               ctx, "cannot create group /xdmf");
  const hsize_t dims = 0;
  const hsize_t max_dims = H5S_UNLIMITED;
  h5::Handle space = h5::dataspace(H5Screate_simple(1, &dims, &max_dims), ctx,
                                   std::string("cannot create dataspace for ") + kVertexIds);
  h5::Handle dcpl = h5::plist(H5Pcreate(H5P_DATASET_CREATE), ctx,
                              std::string("cannot create creation properties for ") + kVertexIds);
  h5::check(H5Pset_chunk(dcpl.get(), 1, &kVertexIdChunk), ctx,
            std::string("cannot chunk ") + kVertexIds);
  h5::check(H5Pset_shuffle(dcpl.get()), ctx, std::string("cannot shuffle ") + kVertexIds);
  h5::check(H5Pset_deflate(dcpl.get(), 4), ctx, std::string("cannot deflate ") + kVertexIds);
  vertex_ids = h5::dataset(H5Dcreate2(file.get(), kVertexIds, H5T_STD_I32LE, space.get(),
                                      H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                           ctx, std::string("cannot create dataset ") + kVertexIds);
  h5::check(group.close(), ctx, "cannot close group /xdmf");
}

void RunFile::Impl::grow_vertex_ids(std::size_t count) {
  if (count <= vertex_id_count) return;
  if (count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw std::invalid_argument(ctx + ": too many particles for XDMF int32 connectivity");
  }
  const hsize_t new_count = count;
  h5::check(H5Dset_extent(vertex_ids.get(), &new_count), ctx,
            std::string("cannot extend ") + kVertexIds);
  std::vector<std::int32_t> ids(count - vertex_id_count);
  std::iota(ids.begin(), ids.end(), static_cast<std::int32_t>(vertex_id_count));
  const hsize_t start = vertex_id_count;
  const hsize_t n = ids.size();
  h5::Handle file_space = h5::dataspace(H5Dget_space(vertex_ids.get()), ctx,
                                        std::string("cannot get the dataspace of ") + kVertexIds);
  h5::check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &start, nullptr, &n, nullptr),
            ctx, std::string("cannot select new rows of ") + kVertexIds);
  h5::Handle mem_space = h5::dataspace(H5Screate_simple(1, &n, nullptr), ctx,
                                       "cannot create a memory dataspace");
  h5::check(H5Dwrite(vertex_ids.get(), H5T_NATIVE_INT32, mem_space.get(), file_space.get(),
                     H5P_DEFAULT, ids.data()),
            ctx, std::string("cannot write ") + kVertexIds);
  vertex_id_count = new_count;
}

RunFile::RunFile(const std::filesystem::path& out_dir, const std::string& scene_text,
                 const std::map<std::string, std::string>& attributes)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const std::filesystem::path h5_path = out_dir / kH5Name;
  m.ctx = h5_path.string();
  if (attributes.count("scene") != 0) {
    throw std::invalid_argument(m.ctx + ": 'scene' is reserved for the scene text attribute");
  }
  std::filesystem::create_directories(out_dir);
  // A link planted where run.h5 goes is removed, not followed: the file is created anew.
  if (std::filesystem::is_symlink(h5_path)) std::filesystem::remove(h5_path);
  h5::silence_auto_errors();
  if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0) h5::fail(m.ctx, "deflate filter not available");

  // STRONG close degree: H5Fclose also closes anything we might have missed, so nothing leaks.
  h5::Handle fapl = h5::plist(H5Pcreate(H5P_FILE_ACCESS), m.ctx, "cannot create access list");
  h5::check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), m.ctx,
            "cannot set the close degree");
  m.file = h5::file(H5Fcreate(m.ctx.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), m.ctx,
                    "cannot create file");

  h5::write_string_attribute(m.file.get(), "scene", scene_text, m.ctx + ": /");
  for (const auto& [name, value] : attributes) {
    h5::write_string_attribute(m.file.get(), name, value, m.ctx + ": /");
  }
  h5::Handle frames = h5::group(H5Gcreate2(m.file.get(), "/frames", H5P_DEFAULT, H5P_DEFAULT,
                                           H5P_DEFAULT),
                                m.ctx, "cannot create group /frames");
  h5::check(frames.close(), m.ctx, "cannot close group /frames");
  m.timeseries.emplace(m.file.get(), m.ctx);
  m.create_vertex_ids();
  m.flush();
  m.xdmf.emplace(out_dir / kXdmfName, kH5Name, kVertexIds);
  m.xdmf->write(0);
  m.open = true;
}

RunFile::RunFile() : impl_(std::make_unique<Impl>()) {}

namespace {
herr_t collect_child(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

std::vector<std::string> children(hid_t loc, const std::string& path, const std::string& ctx) {
  h5::Handle group = h5::group(H5Gopen2(loc, path.c_str(), H5P_DEFAULT), ctx,
                               "cannot open group " + path);
  std::vector<std::string> names;
  hsize_t index = 0;
  h5::check(H5Literate(group.get(), H5_INDEX_NAME, H5_ITER_INC, &index, collect_child, &names),
            ctx, "cannot list " + path);
  return names;
}
}  // namespace

std::optional<std::string> stored_scene_text(const std::filesystem::path& out_dir) {
  const std::string path = (out_dir / kH5Name).string();
  h5::silence_auto_errors();
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    return std::nullopt;
  }
  try {
    h5::Handle file = h5::file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), path, "cannot open");
    return h5::read_string_attribute(file.get(), "scene", path + ": /");
  } catch (const std::runtime_error&) {
    return std::nullopt;
  }
}

std::unique_ptr<RunFile> RunFile::resume(const std::filesystem::path& out_dir,
                                         const RunFileExtent& extent,
                                         const std::vector<std::string>& field_order,
                                         const std::map<std::string, std::string>& attributes) {
  std::unique_ptr<RunFile> run(new RunFile());
  Impl& m = *run->impl_;
  const std::filesystem::path h5_path = out_dir / kH5Name;
  m.ctx = h5_path.string();
  h5::silence_auto_errors();
  if (H5Fis_hdf5(m.ctx.c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    throw std::runtime_error(m.ctx + ": missing or not readable: the interrupted run's output is "
                                     "needed to resume it");
  }
  h5::Handle fapl = h5::plist(H5Pcreate(H5P_FILE_ACCESS), m.ctx, "cannot create access list");
  h5::check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), m.ctx,
            "cannot set the close degree");
  m.file = h5::file(H5Fopen(m.ctx.c_str(), H5F_ACC_RDWR, fapl.get()), m.ctx, "cannot open");
  const hid_t file = m.file.get();

  // Frames after the checkpoint go; the others are indexed again, in the order written.
  std::vector<XdmfFrame> kept;
  for (const std::string& name : children(file, "/frames", m.ctx)) {
    const std::string path = "/frames/" + name;
    const std::uint64_t index = std::strtoull(name.c_str(), nullptr, 10);
    if (index >= extent.frames) {
      h5::check(H5Ldelete(file, path.c_str(), H5P_DEFAULT), m.ctx, "cannot remove " + path);
      continue;
    }
    h5::Handle group = h5::group(H5Gopen2(file, path.c_str(), H5P_DEFAULT), m.ctx,
                                 "cannot open " + path);
    XdmfFrame frame{path, 0.0, 0, {}};
    h5::read_scalar_attribute(group.get(), "time_s", H5T_NATIVE_DOUBLE, &frame.time_s, m.ctx);
    std::vector<std::string> fields = children(file, path, m.ctx);
    std::stable_sort(fields.begin(), fields.end(), [&](const std::string& a, const std::string& b) {
      auto rank = [&](const std::string& f) {
        return std::find(field_order.begin(), field_order.end(), f) - field_order.begin();
      };
      return rank(a) < rank(b);
    });
    for (const std::string& f : fields) {
      h5::Handle set = h5::dataset(H5Dopen2(group.get(), f.c_str(), H5P_DEFAULT), m.ctx,
                                   "cannot open " + path + "/" + f);
      h5::Handle space = h5::dataspace(H5Dget_space(set.get()), m.ctx, "no dataspace");
      hsize_t dims[2] = {0, 1};
      const int rank = H5Sget_simple_extent_ndims(space.get());
      H5Sget_simple_extent_dims(space.get(), dims, nullptr);
      frame.particle_count = dims[0];
      frame.fields.push_back({f, rank == 2 ? static_cast<int>(dims[1]) : 1});
    }
    kept.push_back(std::move(frame));
  }
  if (kept.size() != extent.frames) {
    throw std::runtime_error(m.ctx + ": holds " + std::to_string(kept.size()) +
                             " of the frames the checkpoint recorded (" +
                             std::to_string(extent.frames) + ")");
  }
  std::sort(kept.begin(), kept.end(),
            [](const XdmfFrame& a, const XdmfFrame& b) { return a.group < b.group; });

  m.timeseries.emplace(file, m.ctx, "/timeseries", extent.timeseries_rows,
                       extent.timeseries_columns);
  for (const std::string& table : children(file, "/", m.ctx)) {
    if (table == "timeseries" || table == "frames" || table == "xdmf") continue;
    const auto rows = extent.table_rows.find(table);
    if (rows == extent.table_rows.end() || rows->second == 0) {
      // Created after the checkpoint: created again when its first row comes.
      h5::check(H5Ldelete(file, ("/" + table).c_str(), H5P_DEFAULT), m.ctx,
                "cannot remove /" + table);
      continue;
    }
    const auto columns = extent.table_columns.find(table);
    m.tables.emplace(std::piecewise_construct, std::forward_as_tuple(table),
                     std::forward_as_tuple(file, m.ctx, "/" + table, rows->second,
                                           columns == extent.table_columns.end()
                                               ? std::vector<std::string>{}
                                               : columns->second));
  }
  m.vertex_ids = h5::dataset(H5Dopen2(file, kVertexIds, H5P_DEFAULT), m.ctx,
                             std::string("cannot open ") + kVertexIds);
  {
    h5::Handle space = h5::dataspace(H5Dget_space(m.vertex_ids.get()), m.ctx, "no dataspace");
    H5Sget_simple_extent_dims(space.get(), &m.vertex_id_count, nullptr);
  }
  for (const auto& [name, value] : attributes) {
    h5::write_string_attribute(file, name, value, m.ctx + ": /");
  }
  m.flush();
  m.xdmf.emplace(out_dir / kXdmfName, kH5Name, kVertexIds);
  for (XdmfFrame& f : kept) m.xdmf->add_frame(std::move(f));
  m.frames = extent.frames;
  m.xdmf->write(static_cast<std::size_t>(m.vertex_id_count));
  m.open = true;
  return run;
}

RunFileExtent RunFile::extent() const {
  const Impl& m = *impl_;
  RunFileExtent e;
  e.timeseries_rows = m.timeseries->rows();
  e.timeseries_columns = m.timeseries->columns();
  for (const auto& [name, table] : m.tables) {
    e.table_rows[name] = table.rows();
    e.table_columns[name] = table.columns();
  }
  e.frames = m.frames;
  return e;
}

RunFile::~RunFile() {
  try {
    close();
  } catch (const std::exception& e) {
    // A destructor must not throw; still leave a trace that the file may be incomplete.
    std::fprintf(stderr, "rockcut: closing run file failed: %s\n", e.what());
  } catch (...) {
  }
}

void RunFile::append_timeseries(double time_s, std::uint64_t step,
                                const std::vector<std::pair<std::string, double>>& scalars) {
  impl_->require_open();
  impl_->require_room(impl_->timeseries->growth_bound_bytes(scalars));
  impl_->timeseries->append(time_s, step, scalars);
}

void RunFile::append_record(const std::string& table, double time_s, std::uint64_t step,
                            const std::vector<std::pair<std::string, double>>& values) {
  Impl& m = *impl_;
  m.require_open();
  if (!is_valid_dataset_name(table) || table == "timeseries" || table == "frames" ||
      table == "xdmf") {
    throw std::invalid_argument(m.ctx + ": invalid table name \"" + table + "\"");
  }
  auto it = m.tables.find(table);
  if (it == m.tables.end()) {
    it = m.tables.emplace(std::piecewise_construct, std::forward_as_tuple(table),
                          std::forward_as_tuple(m.file.get(), m.ctx, "/" + table))
             .first;
  }
  m.require_room(it->second.growth_bound_bytes(values));
  it->second.append(time_s, step, values);
}

void RunFile::write_frame(double time_s, std::uint64_t step, std::size_t particle_count,
                          const std::vector<FrameField>& fields) {
  Impl& m = *impl_;
  m.require_open();
  if (!std::isfinite(time_s)) {
    throw std::invalid_argument(m.ctx + ": frame time is not finite");  // XDMF needs a real time
  }
  validate_frame_fields(particle_count, fields, m.ctx);
  // The frame's values uncompressed (deflate can only shrink them, bar a few bytes per block),
  // each dataset's header and chunk index, the group, and the vertex ids it adds.
  std::uint64_t frame_bytes = 8192;
  for (const FrameField& field : fields) frame_bytes += field.values.size() * sizeof(double) + 8192;
  if (particle_count > m.vertex_id_count) {
    frame_bytes += (particle_count - m.vertex_id_count) * sizeof(std::int32_t) + 4096;
  }
  m.require_room(frame_bytes);
  const std::string path = frame_group_path(m.frames);
  try {
    write_frame_group(m.file.get(), path, time_s, step, particle_count, fields, m.ctx);
    m.grow_vertex_ids(particle_count);
    // Flush before publishing the frame in the XDMF, so the index never points at unwritten data.
    m.flush();
  } catch (...) {
    // Drop the half-written group so the next frame can reuse its name; best effort only.
    if (H5Lexists(m.file.get(), path.c_str(), H5P_DEFAULT) > 0) {
      H5Ldelete(m.file.get(), path.c_str(), H5P_DEFAULT);
    }
    H5Eclear2(H5E_DEFAULT);
    throw;
  }
  XdmfFrame frame{path, time_s, particle_count, {}};
  for (const FrameField& field : fields) frame.fields.push_back({field.name, field.components});
  m.xdmf->add_frame(std::move(frame));
  ++m.frames;
  m.xdmf->write(static_cast<std::size_t>(m.vertex_id_count));
}

void RunFile::set_attribute(const std::string& name, const std::string& value) {
  Impl& m = *impl_;
  m.require_open();
  // A status attribute comes as the run stops, often for want of room: it may use most of the
  // reserve kept for the close.
  m.require_room(name.size() + value.size() + 4096, kCloseReserveBytes / 4);
  h5::write_string_attribute(m.file.get(), name, value, m.ctx + ": /");
  // Status attributes are often written just before a failure exit: get them to disk now.
  m.flush();
}

std::size_t RunFile::frame_count() const { return impl_->frames; }

void RunFile::flush() {
  impl_->require_open();
  impl_->flush();
}

void RunFile::close() {
  if (!impl_ || !impl_->open) return;
  Impl& m = *impl_;
  m.open = false;  // even if closing fails below, never try again (idempotent)
  std::string first_error;
  auto note = [&](const std::exception& e) {
    if (first_error.empty()) first_error = e.what();
  };
  try {
    m.flush();
  } catch (const std::exception& e) {
    note(e);
  }
  try {
    m.timeseries->close();
  } catch (const std::exception& e) {
    note(e);
  }
  for (auto& [name, table] : m.tables) {
    try {
      table.close();
    } catch (const std::exception& e) {
      note(e);
    }
  }
  if (m.vertex_ids.close() < 0 && first_error.empty()) {
    first_error = m.ctx + ": cannot close " + kVertexIds + " (HDF5: " + h5::take_error_stack() + ")";
  }
  if (m.file.close() < 0 && first_error.empty()) {
    first_error = m.ctx + ": cannot close file (HDF5: " + h5::take_error_stack() + ")";
  }
  if (!first_error.empty()) throw std::runtime_error(first_error);
}

}  // namespace rockcut::coupler
