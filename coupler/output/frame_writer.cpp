#include "output/frame_writer.hpp"

#include <algorithm>
#include <stdexcept>
#include <unordered_set>

#include "output/timeseries.hpp"

namespace rockcut::coupler {

hsize_t frame_chunk_rows(std::size_t particle_count, int components) {
  const hsize_t rows = kFrameChunkValues / static_cast<hsize_t>(components);
  return std::min<hsize_t>(rows, particle_count);
}

void validate_frame_fields(std::size_t particle_count, const std::vector<FrameField>& fields,
                           const std::string& context) {
  std::unordered_set<std::string> names;
  bool has_position = false;
  for (const FrameField& field : fields) {
    // ':' would end the file part of an XDMF "run.h5:/frames/..." reference early.
    if (!is_valid_dataset_name(field.name) || field.name.find(':') != std::string::npos) {
      throw std::invalid_argument(context + ": invalid frame field name '" + field.name + "'");
    }
    if (!names.insert(field.name).second) {
      throw std::invalid_argument(context + ": frame field '" + field.name + "' given twice");
    }
    if (field.components != 1 && field.components != 2) {
      throw std::invalid_argument(context + ": frame field '" + field.name + "' has " +
                                  std::to_string(field.components) +
                                  " components (1 or 2 allowed)");
    }
    const std::size_t expected = particle_count * static_cast<std::size_t>(field.components);
    if (field.values.size() != expected) {
      throw std::invalid_argument(context + ": frame field '" + field.name + "' has " +
                                  std::to_string(field.values.size()) + " values, expected " +
                                  std::to_string(expected));
    }
    if (field.name == "position") {
      if (field.components != 2) {
        throw std::invalid_argument(context + ": frame field 'position' must have 2 components");
      }
      has_position = true;
    }
  }
  if (!has_position) throw std::invalid_argument(context + ": frame has no 'position' field");
}

namespace {

void write_field(hid_t group, const std::string& group_path, std::size_t particle_count,
                 const FrameField& field, const std::string& ctx) {
  const std::string where = group_path + "/" + field.name;
  const int rank = field.components == 1 ? 1 : 2;
  const hsize_t dims[2] = {particle_count, static_cast<hsize_t>(field.components)};
  const hsize_t chunk[2] = {frame_chunk_rows(particle_count, field.components), dims[1]};
  h5::Handle space = h5::dataspace(H5Screate_simple(rank, dims, nullptr), ctx,
                                   "cannot create dataspace for " + where);
  h5::Handle dcpl = h5::plist(H5Pcreate(H5P_DATASET_CREATE), ctx,
                              "cannot create creation properties for " + where);
  h5::check(H5Pset_chunk(dcpl.get(), rank, chunk), ctx, "cannot chunk " + where);
  // Shuffle groups the bytes of the doubles by significance; deflate then compresses far better.
  h5::check(H5Pset_shuffle(dcpl.get()), ctx, "cannot add the shuffle filter to " + where);
  h5::check(H5Pset_deflate(dcpl.get(), 4), ctx, "cannot add the deflate filter to " + where);
  h5::Handle dataset = h5::dataset(H5Dcreate2(group, field.name.c_str(), H5T_IEEE_F64LE,
                                              space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                                   ctx, "cannot create dataset " + where);
  h5::check(H5Dwrite(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                     field.values.data()),
            ctx, "cannot write dataset " + where);
  h5::check(dataset.close(), ctx, "cannot close dataset " + where);
}

}  // namespace

void write_frame_group(hid_t file, const std::string& path, double time_s, std::uint64_t step,
                       std::size_t particle_count, const std::vector<FrameField>& fields,
                       const std::string& ctx) {
  h5::Handle group = h5::group(
      H5Gcreate2(file, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), ctx,
      "cannot create group " + path);
  h5::write_scalar_attribute(group.get(), "time_s", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, &time_s,
                             ctx + ": " + path);
  h5::write_scalar_attribute(group.get(), "step", H5T_NATIVE_UINT64, H5T_STD_U64LE, &step,
                             ctx + ": " + path);
  if (particle_count > 0) {
    for (const FrameField& field : fields) write_field(group.get(), path, particle_count, field, ctx);
  }
  h5::check(group.close(), ctx, "cannot close group " + path);
}

}  // namespace rockcut::coupler
