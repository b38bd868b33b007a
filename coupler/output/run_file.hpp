// run.h5 and run.xdmf: the scene, versions, a time series and per-particle frames of one run.
// Written by the coupler only. The file is flushed after every frame and the XDMF rewritten, so a
// run that stops early (crash, signal) leaves both readable up to the last frame.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rockcut::coupler {

/// One per-particle field of a frame: `components` values per particle, interleaved.
struct FrameField {
  std::string name;  ///< "position", "velocity", "radius", "force", "pressure", ...
  int components = 1;
  std::span<const double> values;  ///< particle_count * components values
};

/// How far a run had written run.h5 when a checkpoint was taken: a resumed run cuts the file back
/// to it, so that what the interrupted run wrote after the checkpoint is dropped, not duplicated.
struct RunFileExtent {
  std::uint64_t timeseries_rows = 0;
  std::vector<std::string> timeseries_columns;
  std::map<std::string, std::uint64_t> table_rows;  ///< event tables such as /breaks
  std::map<std::string, std::vector<std::string>> table_columns;
  std::uint64_t frames = 0;
};

/// The effective scene stored in OUT/run.h5 by the run that made it; none where the file is
/// missing or unreadable.
std::optional<std::string> stored_scene_text(const std::filesystem::path& out_dir);

class RunFile {
 public:
  /// Creates OUT/run.h5 (truncating) and OUT/run.xdmf. `scene_text` and `attributes` (versions,
  /// transport, ...) are stored as string attributes on the root group.
  RunFile(const std::filesystem::path& out_dir, const std::string& scene_text,
          const std::map<std::string, std::string>& attributes);
  /// Reopens OUT/run.h5 of an interrupted run, cuts it back to `extent`, rewrites run.xdmf from
  /// the frames that stay (their fields in the order of `field_order`) and stores `attributes`.
  static std::unique_ptr<RunFile> resume(const std::filesystem::path& out_dir,
                                         const RunFileExtent& extent,
                                         const std::vector<std::string>& field_order,
                                         const std::map<std::string, std::string>& attributes);
  /// What has been written so far (for a checkpoint).
  RunFileExtent extent() const;
  ~RunFile();
  RunFile(const RunFile&) = delete;
  RunFile& operator=(const RunFile&) = delete;

  /// Appends one row to /timeseries: dataset /timeseries/time_s and one 1-D dataset per name
  /// (chunked, extendible). Names may appear late (earlier rows are NaN) and may be missing in a row
  /// (NaN).
  void append_timeseries(double time_s, std::uint64_t step,
                         const std::vector<std::pair<std::string, double>>& scalars);

  /// Appends one row to the event table /<table> (created on first use), with the same layout as
  /// /timeseries: columns time_s, step and one per value name. Used for the bond-break log.
  void append_record(const std::string& table, double time_s, std::uint64_t step,
                     const std::vector<std::pair<std::string, double>>& values);

  /// Writes frame k as /frames/<k:06d>/<field> (chunked, deflate-compressed) with attributes time_s
  /// and step, flushes, and rewrites run.xdmf. Vector fields must have 2 components; "position" is
  /// required and becomes the XDMF geometry (XY).
  void write_frame(double time_s, std::uint64_t step, std::size_t particle_count,
                   const std::vector<FrameField>& fields);

  /// Stores a string attribute on the root group (e.g. "status" = "failed: ...").
  void set_attribute(const std::string& name, const std::string& value);

  std::size_t frame_count() const;
  /// Gets everything written so far to disk (before a checkpoint records it).
  void flush();

  /// Flushes and closes; idempotent. Called by the destructor.
  void close();

 private:
  RunFile();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockcut::coupler
