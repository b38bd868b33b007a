#include "output/timeseries.hpp"

#include <limits>
#include <stdexcept>

namespace rockcut::coupler {

bool is_valid_dataset_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
         name.find('\0') == std::string::npos;
}

Timeseries::Timeseries(hid_t file, std::string context, std::string group)
    : context_(std::move(context)), group_path_(std::move(group)) {
  group_ = h5::group(
      H5Gcreate2(file, group_path_.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), context_,
      "cannot create group " + group_path_);
  const hsize_t one = 1;
  one_element_ = h5::dataspace(H5Screate_simple(1, &one, nullptr), context_,
                               "cannot create a one-element dataspace");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::uint64_t zero = 0;
  time_ = create_column("time_s", H5T_IEEE_F64LE, &nan);
  step_ = create_column("step", H5T_STD_U64LE, &zero);
}

namespace {
herr_t collect_link_name(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}
}  // namespace

Timeseries::Timeseries(hid_t file, std::string context, std::string group, std::uint64_t rows,
                       const std::vector<std::string>& columns)
    : context_(std::move(context)), group_path_(std::move(group)) {
  group_ = h5::group(H5Gopen2(file, group_path_.c_str(), H5P_DEFAULT), context_,
                     "cannot open group " + group_path_);
  const hsize_t one = 1;
  one_element_ = h5::dataspace(H5Screate_simple(1, &one, nullptr), context_,
                               "cannot create a one-element dataspace");
  std::vector<std::string> present;
  hsize_t index = 0;
  h5::check(H5Literate(group_.get(), H5_INDEX_NAME, H5_ITER_INC, &index, collect_link_name,
                       &present),
            context_, "cannot list " + group_path_);
  auto open_cut = [&](const std::string& name) {
    Column column{name, h5::dataset(H5Dopen2(group_.get(), name.c_str(), H5P_DEFAULT), context_,
                                    "cannot open " + where(name))};
    h5::Handle space = h5::dataspace(H5Dget_space(column.dataset.get()), context_,
                                     "cannot get the dataspace of " + where(name));
    hsize_t have = 0;
    H5Sget_simple_extent_dims(space.get(), &have, nullptr);
    if (have < rows) {
      throw std::runtime_error(context_ + ": " + where(name) + " has " + std::to_string(have) +
                               " rows, the checkpoint recorded " + std::to_string(rows));
    }
    const hsize_t cut = rows;
    h5::check(H5Dset_extent(column.dataset.get(), &cut), context_, "cannot cut " + where(name));
    return column;
  };
  time_ = open_cut("time_s");
  step_ = open_cut("step");
  for (const std::string& name : columns) {
    index_.emplace(name, scalars_.size());
    scalars_.push_back(open_cut(name));
    seen_in_call_.push_back(0);
  }
  // Columns the interrupted run created after the checkpoint are created again when they come.
  for (const std::string& name : present) {
    if (name == "time_s" || name == "step" || index_.count(name)) continue;
    h5::check(H5Ldelete(group_.get(), name.c_str(), H5P_DEFAULT), context_,
              "cannot remove " + where(name));
  }
  rows_ = rows;
}

std::vector<std::string> Timeseries::columns() const {
  std::vector<std::string> out;
  for (const Column& c : scalars_) out.push_back(c.name);
  return out;
}

std::string Timeseries::where(const std::string& column) const {
  return group_path_ + "/" + column;
}

Timeseries::Column Timeseries::create_column(const std::string& name, hid_t file_type,
                                             const void* fill) {
  // Starts with the current row count: the fill value (NaN) stands for the rows before it existed.
  const hsize_t dims = rows_;
  const hsize_t max_dims = H5S_UNLIMITED;
  h5::Handle space = h5::dataspace(H5Screate_simple(1, &dims, &max_dims), context_,
                                   "cannot create dataspace for " + where(name));
  h5::Handle dcpl = h5::plist(H5Pcreate(H5P_DATASET_CREATE), context_,
                              "cannot create creation properties for " + where(name));
  const hsize_t chunk = kChunkRows;
  h5::check(H5Pset_chunk(dcpl.get(), 1, &chunk), context_, "cannot chunk " + where(name));
  // The fill value is converted from the same type as the file type: NaN or 0 exactly.
  h5::check(H5Pset_fill_value(dcpl.get(), file_type, fill), context_,
            "cannot set the fill value of " + where(name));
  h5::check(H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_ALLOC), context_,
            "cannot set the fill time of " + where(name));
  Column column{name, h5::dataset(H5Dcreate2(group_.get(), name.c_str(), file_type, space.get(),
                                             H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                                  context_, "cannot create dataset " + where(name))};
  return column;
}

std::uint64_t Timeseries::growth_bound_bytes(
    const std::vector<std::pair<std::string, double>>& scalars) const {
  constexpr std::uint64_t kChunkBytes = kChunkRows * sizeof(double);
  constexpr std::uint64_t kHeaderBytes = 4096;  // object header, chunk index, link in the group
  std::uint64_t bytes = 0;
  if (rows_ % kChunkRows == 0) bytes += (scalars_.size() + 2) * (kChunkBytes + kHeaderBytes);
  for (const auto& [name, value] : scalars) {
    if (index_.count(name) == 0) bytes += (rows_ / kChunkRows + 1) * kChunkBytes + kHeaderBytes;
  }
  return bytes;
}

void Timeseries::extend(Column& column) {
  const hsize_t new_rows = rows_ + 1;
  h5::check(H5Dset_extent(column.dataset.get(), &new_rows), context_,
            "cannot extend " + where(column.name));
}

void Timeseries::write_last_row(Column& column, hid_t mem_type, const void* value) {
  h5::Handle file_space = h5::dataspace(H5Dget_space(column.dataset.get()), context_,
                                        "cannot get the dataspace of " + where(column.name));
  const hsize_t start = rows_;
  const hsize_t count = 1;
  h5::check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &start, nullptr, &count,
                                nullptr),
            context_, "cannot select a row of " + where(column.name));
  h5::check(H5Dwrite(column.dataset.get(), mem_type, one_element_.get(), file_space.get(),
                     H5P_DEFAULT, value),
            context_, "cannot write a row of " + where(column.name));
}

void Timeseries::append(double time_s, std::uint64_t step,
                        const std::vector<std::pair<std::string, double>>& scalars) {
  if (!group_.valid()) throw std::logic_error(context_ + ": timeseries is closed");
  if (broken_) {
    throw std::logic_error(context_ + ": timeseries unusable after an earlier write error");
  }
  // Validate the whole row before touching the file so a bad row leaves no partial trace.
  ++call_;
  std::vector<std::size_t> targets;  // per scalar: column position, or npos if new
  targets.reserve(scalars.size());
  std::unordered_map<std::string, std::size_t> fresh;  // new names in this row -> first index
  for (std::size_t i = 0; i < scalars.size(); ++i) {
    const std::string& name = scalars[i].first;
    if (!is_valid_dataset_name(name) || name == "time_s" || name == "step") {
      throw std::invalid_argument(context_ + ": invalid timeseries column name '" + name + "'");
    }
    const auto known = index_.find(name);
    bool repeated = false;
    if (known == index_.end()) {
      repeated = !fresh.emplace(name, i).second;
    } else {
      // Stamping with a per-call counter detects repeats in O(1) without clearing anything.
      repeated = seen_in_call_[known->second] == call_;
      seen_in_call_[known->second] = call_;
    }
    if (repeated) {
      throw std::invalid_argument(context_ + ": timeseries column '" + name +
                                  "' given twice in one row");
    }
    targets.push_back(known == index_.end() ? std::string::npos : known->second);
  }

  try {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t i = 0; i < scalars.size(); ++i) {
      if (targets[i] != std::string::npos) continue;
      scalars_.push_back(create_column(scalars[i].first, H5T_IEEE_F64LE, &nan));
      seen_in_call_.push_back(call_);
      targets[i] = scalars_.size() - 1;
      index_.emplace(scalars[i].first, targets[i]);
    }
    // Every column grows by one row; columns absent from this row keep the NaN fill value.
    extend(time_);
    extend(step_);
    for (Column& column : scalars_) extend(column);
    write_last_row(time_, H5T_NATIVE_DOUBLE, &time_s);
    write_last_row(step_, H5T_NATIVE_UINT64, &step);
    for (std::size_t i = 0; i < scalars.size(); ++i) {
      write_last_row(scalars_[targets[i]], H5T_NATIVE_DOUBLE, &scalars[i].second);
    }
  } catch (...) {
    broken_ = true;
    throw;
  }
  ++rows_;
}

void Timeseries::close() {
  std::string first_error;
  auto close_one = [&](h5::Handle& handle, const std::string& what) {
    if (handle.close() < 0 && first_error.empty()) {
      first_error = context_ + ": cannot close " + what;
      const std::string stack = h5::take_error_stack();
      if (!stack.empty()) first_error += " (HDF5: " + stack + ")";
    }
  };
  for (Column& column : scalars_) close_one(column.dataset, where(column.name));
  close_one(time_.dataset, where("time_s"));
  close_one(step_.dataset, where("step"));
  close_one(one_element_, "a dataspace");
  close_one(group_, group_path_);
  if (!first_error.empty()) throw std::runtime_error(first_error);
}

}  // namespace rockcut::coupler
