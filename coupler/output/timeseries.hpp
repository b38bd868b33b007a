// /timeseries in run.h5: one extendible 1-D dataset per column, one row per coupling step.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "output/h5_handle.hpp"

namespace rockcut::coupler {

class Timeseries {
 public:
  static constexpr hsize_t kChunkRows = 1024;

  /// Creates the group `group` (default /timeseries) with the time_s (float64) and step (uint64)
  /// columns under `file`. `context` (the file name) prefixes every error message. The same table
  /// form stores event logs such as /breaks (one row per bond break).
  Timeseries(hid_t file, std::string context, std::string group = "/timeseries");
  /// Reopens the existing table `group` of a resumed run, cut back to its first `rows` rows and
  /// to the columns `columns` (besides time_s and step): what a checkpoint recorded of it.
  Timeseries(hid_t file, std::string context, std::string group, std::uint64_t rows,
             const std::vector<std::string>& columns);
  /// The value columns in the order they were created.
  std::vector<std::string> columns() const;

  /// Appends one row. A column first seen now is created with NaN for the earlier rows; a known
  /// column missing from `scalars` gets NaN (the dataset fill value). O(columns), never O(rows).
  void append(double time_s, std::uint64_t step,
              const std::vector<std::pair<std::string, double>>& scalars);

  std::size_t rows() const { return static_cast<std::size_t>(rows_); }

  /// The most the file can grow by appending this row: a new chunk of every column when the row
  /// starts one, and each column first seen now (its chunks up to this row and its header).
  std::uint64_t growth_bound_bytes(const std::vector<std::pair<std::string, double>>& scalars) const;

  /// Closes every dataset and the group, throwing on the first failure (all are released anyway).
  void close();

 private:
  struct Column {
    std::string name;
    h5::Handle dataset;
  };

  Column create_column(const std::string& name, hid_t file_type, const void* fill);
  void extend(Column& column);
  void write_last_row(Column& column, hid_t mem_type, const void* value);
  std::string where(const std::string& column) const;

  std::string context_;
  std::string group_path_;
  h5::Handle group_;
  h5::Handle one_element_;  // memory dataspace of one value, reused by every write
  Column time_;
  Column step_;
  std::vector<Column> scalars_;
  std::unordered_map<std::string, std::size_t> index_;  // name -> position in scalars_
  std::vector<std::uint64_t> seen_in_call_;  // per column: the last append call naming it
  std::uint64_t call_ = 0;
  hsize_t rows_ = 0;
  bool broken_ = false;  // an append failed half-way: columns may differ in length
};

/// True if `name` can be used as a dataset name (non-empty, no '/', not "." or "..").
bool is_valid_dataset_name(const std::string& name);

}  // namespace rockcut::coupler
