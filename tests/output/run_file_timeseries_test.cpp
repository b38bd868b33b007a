// run.h5 /timeseries and root attributes, read back with the plain HDF5 C API.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "output/h5_handle.hpp"
#include "output/run_file.hpp"

namespace rockcut::coupler::testing {
// Defined in h5_read_util.cpp.
std::filesystem::path scratch_dir(const std::string& name);
h5::Handle open_read_only(const std::filesystem::path& file);
std::vector<hsize_t> dataset_dims(hid_t file, const std::string& path);
std::vector<double> read_doubles(hid_t file, const std::string& path);
std::vector<std::uint64_t> read_u64s(hid_t file, const std::string& path);
std::string read_string_attribute(hid_t loc, const std::string& name);
std::vector<std::string> attribute_names(hid_t loc);

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Element-wise equality where NaN only equals NaN (EXPECT_EQ would treat NaN != NaN).
void expect_same(const std::vector<double>& actual, const std::vector<double>& expected,
                 const std::string& what) {
  ASSERT_EQ(actual.size(), expected.size()) << what;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (std::isnan(expected[i])) {
      EXPECT_TRUE(std::isnan(actual[i])) << what << "[" << i << "] = " << actual[i];
    } else {
      EXPECT_EQ(actual[i], expected[i]) << what << "[" << i << "]";
    }
  }
}

TEST(RunFileTimeseries, LateAndMissingNamesAreNaN) {
  const auto dir = scratch_dir("timeseries_small");
  {
    RunFile run(dir, "scene", {});
    run.append_timeseries(0.0, 0, {{"a", 1.0}});
    run.append_timeseries(0.5, 10, {{"a", 2.0}, {"b", 20.0}});
    run.append_timeseries(1.0, 20, {{"b", 30.0}});              // a missing
    run.append_timeseries(1.5, 30, {{"c", -1.0}, {"a", 4.0}});  // c appears late
    run.append_timeseries(2.0, 40, {});                         // everything missing
    run.close();
  }
  h5::Handle file = open_read_only(dir / "run.h5");
  expect_same(read_doubles(file.get(), "/timeseries/time_s"), {0.0, 0.5, 1.0, 1.5, 2.0}, "time");
  EXPECT_EQ(read_u64s(file.get(), "/timeseries/step"),
            (std::vector<std::uint64_t>{0, 10, 20, 30, 40}));
  expect_same(read_doubles(file.get(), "/timeseries/a"), {1.0, 2.0, kNaN, 4.0, kNaN}, "a");
  expect_same(read_doubles(file.get(), "/timeseries/b"), {kNaN, 20.0, 30.0, kNaN, kNaN}, "b");
  expect_same(read_doubles(file.get(), "/timeseries/c"), {kNaN, kNaN, kNaN, -1.0, kNaN}, "c");
}

TEST(RunFileTimeseries, ManyRowsAcrossChunksAreChunkedAndUnlimited) {
  const auto dir = scratch_dir("timeseries_large");
  constexpr std::size_t kRows = 2600;  // > 2 chunks of 1024
  constexpr std::size_t kLate = 1500;
  {
    RunFile run(dir, "scene", {});
    for (std::size_t i = 0; i < kRows; ++i) {
      std::vector<std::pair<std::string, double>> row;
      if (i % 2 == 0) row.emplace_back("even", static_cast<double>(i) * 0.25);
      if (i >= kLate) row.emplace_back("late", -static_cast<double>(i));
      run.append_timeseries(static_cast<double>(i) * 1e-3, i * 7, row);
    }
  }  // destructor closes
  h5::Handle file = open_read_only(dir / "run.h5");
  std::vector<double> time(kRows), even(kRows), late(kRows);
  std::vector<std::uint64_t> step(kRows);
  for (std::size_t i = 0; i < kRows; ++i) {
    time[i] = static_cast<double>(i) * 1e-3;
    step[i] = i * 7;
    even[i] = i % 2 == 0 ? static_cast<double>(i) * 0.25 : kNaN;
    late[i] = i >= kLate ? -static_cast<double>(i) : kNaN;
  }
  expect_same(read_doubles(file.get(), "/timeseries/time_s"), time, "time");
  EXPECT_EQ(read_u64s(file.get(), "/timeseries/step"), step);
  expect_same(read_doubles(file.get(), "/timeseries/even"), even, "even");
  expect_same(read_doubles(file.get(), "/timeseries/late"), late, "late");

  for (const char* name : {"/timeseries/time_s", "/timeseries/step", "/timeseries/late"}) {
    SCOPED_TRACE(name);
    h5::Handle dset = h5::dataset(H5Dopen2(file.get(), name, H5P_DEFAULT), name, "open");
    h5::Handle dcpl = h5::plist(H5Dget_create_plist(dset.get()), name, "dcpl");
    EXPECT_EQ(H5Pget_layout(dcpl.get()), H5D_CHUNKED);
    hsize_t chunk = 0;
    EXPECT_EQ(H5Pget_chunk(dcpl.get(), 1, &chunk), 1);
    EXPECT_EQ(chunk, 1024u);
    h5::Handle space = h5::dataspace(H5Dget_space(dset.get()), name, "space");
    hsize_t dims = 0;
    hsize_t max_dims = 0;
    ASSERT_EQ(H5Sget_simple_extent_dims(space.get(), &dims, &max_dims), 1);
    EXPECT_EQ(dims, kRows);
    EXPECT_EQ(max_dims, H5S_UNLIMITED);
  }
  h5::Handle step_dset =
      h5::dataset(H5Dopen2(file.get(), "/timeseries/step", H5P_DEFAULT), "step", "open");
  h5::Handle step_type = h5::datatype(H5Dget_type(step_dset.get()), "step", "type");
  EXPECT_GT(H5Tequal(step_type.get(), H5T_STD_U64LE), 0);
}

TEST(RunFileTimeseries, RejectsBadRowsWithoutChangingTheFile) {
  const auto dir = scratch_dir("timeseries_bad");
  {
    RunFile run(dir, "scene", {});
    run.append_timeseries(0.0, 0, {{"a", 1.0}});
    EXPECT_THROW(run.append_timeseries(1.0, 1, {{"a", 1.0}, {"a", 2.0}}), std::invalid_argument);
    EXPECT_THROW(run.append_timeseries(1.0, 1, {{"n", 1.0}, {"n", 2.0}}), std::invalid_argument);
    EXPECT_THROW(run.append_timeseries(1.0, 1, {{"x/y", 1.0}}), std::invalid_argument);
    EXPECT_THROW(run.append_timeseries(1.0, 1, {{"time_s", 1.0}}), std::invalid_argument);
    EXPECT_THROW(run.append_timeseries(1.0, 1, {{"", 1.0}}), std::invalid_argument);
    run.append_timeseries(2.0, 2, {{"a", 3.0}});
    run.close();
    EXPECT_THROW(run.append_timeseries(3.0, 3, {}), std::logic_error);
  }
  h5::Handle file = open_read_only(dir / "run.h5");
  expect_same(read_doubles(file.get(), "/timeseries/a"), {1.0, 3.0}, "a");
  EXPECT_EQ(H5Lexists(file.get(), "/timeseries/n", H5P_DEFAULT), 0);
}

TEST(RunFileAttributes, SceneRoundTripsAndSetAttributeOverwrites) {
  const auto dir = scratch_dir("attributes");
  // Longer than the 64 KiB a fixed-size attribute may hold, with UTF-8 and newlines.
  std::string scene = "# scene \xc3\xa9\xe2\x82\xac\n[rock]\nucs_mpa = 30\n";
  while (scene.size() < 100000) scene += "particle_radius_m = 0.001 # padding line\n";
  {
    RunFile run(dir, scene, {{"dem_version", "1.2.3"}, {"transport", "inproc"}});
    run.set_attribute("status", "running");
    run.set_attribute("status", "failed: fluid module exited with code 3");
    run.set_attribute("transport", "tcp");  // overwrite one given to the constructor
    run.close();
    run.close();  // idempotent
    EXPECT_THROW(run.set_attribute("status", "x"), std::logic_error);
  }
  h5::Handle file = open_read_only(dir / "run.h5");
  EXPECT_EQ(read_string_attribute(file.get(), "scene"), scene);
  EXPECT_EQ(read_string_attribute(file.get(), "dem_version"), "1.2.3");
  EXPECT_EQ(read_string_attribute(file.get(), "transport"), "tcp");
  EXPECT_EQ(read_string_attribute(file.get(), "status"),
            "failed: fluid module exited with code 3");
  EXPECT_EQ(attribute_names(file.get()),
            (std::vector<std::string>{"dem_version", "scene", "status", "transport"}));
}

TEST(RunFileAttributes, ReservedAndInvalidNamesAreRejected) {
  const auto dir = scratch_dir("attributes_bad");
  EXPECT_THROW(RunFile(dir, "scene", {{"scene", "other"}}), std::invalid_argument);
  RunFile run(dir, "scene", {});
  EXPECT_THROW(run.set_attribute("", "x"), std::invalid_argument);
  EXPECT_THROW(run.set_attribute("nul", std::string("a\0b", 3)), std::invalid_argument);
}

TEST(RunFileErrors, HdfFailuresNameTheFile) {
  const auto dir = scratch_dir("errors");
  std::filesystem::create_directories(dir / "run.h5");  // a directory where the file should go
  try {
    RunFile run(dir, "scene", {});
    ADD_FAILURE() << "created run.h5 over a directory";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((dir / "run.h5").string()), std::string::npos) << message;
    EXPECT_NE(message.find("cannot create file"), std::string::npos) << message;
    EXPECT_NE(message.find("HDF5:"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace rockcut::coupler::testing
