// One frame group of run.h5: /frames/NNNNNN with time_s, step and one dataset per field.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "output/h5_handle.hpp"
#include "output/run_file.hpp"

namespace rockcut::coupler {

/// Frame datasets are chunked to about this many values (512 KiB of float64): big enough for
/// deflate to work well, small enough to fit HDF5's default 1 MiB chunk cache.
inline constexpr hsize_t kFrameChunkValues = 65536;

/// Rows per chunk for a field of `particle_count` rows (> 0) and `components` columns.
hsize_t frame_chunk_rows(std::size_t particle_count, int components);

/// Throws std::invalid_argument unless the fields are well formed: unique valid names,
/// 1 or 2 components, particle_count * components values, and a 2-component "position".
void validate_frame_fields(std::size_t particle_count, const std::vector<FrameField>& fields,
                           const std::string& context);

/// Creates group `path` under `file` with attributes time_s and step and, if particle_count > 0,
/// one float64 dataset per field (shape (n) or (n, 2); chunked, shuffle + deflate level 4).
void write_frame_group(hid_t file, const std::string& path, double time_s, std::uint64_t step,
                       std::size_t particle_count, const std::vector<FrameField>& fields,
                       const std::string& context);

}  // namespace rockcut::coupler
