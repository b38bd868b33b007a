#include "output/run_file.hpp"

#include <map>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "output/frame_writer.hpp"
#include "output/h5_handle.hpp"
#include "output/timeseries.hpp"
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
  h5::write_string_attribute(m.file.get(), name, value, m.ctx + ": /");
  // Status attributes are often written just before a failure exit: get them to disk now.
  m.flush();
}

std::size_t RunFile::frame_count() const { return impl_->frames; }

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
