// run.h5 /frames: values, attributes, storage layout (chunked + deflate), validation.
#include <gtest/gtest.h>

#include <cmath>

#include "output/frame_writer.hpp"
#include "output/h5_handle.hpp"
#include "output/run_file.hpp"

namespace rockcut::coupler::testing {
// Defined in h5_read_util.cpp.
std::filesystem::path scratch_dir(const std::string& name);
h5::Handle open_read_only(const std::filesystem::path& file);
std::vector<hsize_t> dataset_dims(hid_t file, const std::string& path);
std::vector<double> read_doubles(hid_t file, const std::string& path);
double read_double_attribute(hid_t loc, const std::string& name);
std::uint64_t read_u64_attribute(hid_t loc, const std::string& name);

namespace {

constexpr std::size_t kFrameParticles = 5;

std::vector<double> positions(int frame) {
  std::vector<double> xy;
  for (std::size_t i = 0; i < kFrameParticles; ++i) {
    xy.push_back(0.1 * static_cast<double>(i) + frame);     // x
    xy.push_back(-0.01 * static_cast<double>(i) - frame);   // y
  }
  return xy;
}

std::vector<double> radii(int frame) {
  std::vector<double> r;
  for (std::size_t i = 0; i < kFrameParticles; ++i)
    r.push_back(1e-3 * static_cast<double>(i + 1) / (frame + 1));
  return r;
}

/// Checks that `path` is chunked with the given chunk shape and has deflate at level 4.
void expect_chunked_deflate(hid_t file, const std::string& path,
                            const std::vector<hsize_t>& chunk_expected) {
  SCOPED_TRACE(path);
  h5::Handle dset = h5::dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), path, "open");
  h5::Handle dcpl = h5::plist(H5Dget_create_plist(dset.get()), path, "dcpl");
  ASSERT_EQ(H5Pget_layout(dcpl.get()), H5D_CHUNKED);
  std::vector<hsize_t> chunk(chunk_expected.size());
  EXPECT_EQ(H5Pget_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()),
            static_cast<int>(chunk.size()));
  EXPECT_EQ(chunk, chunk_expected);
  unsigned flags = 0;
  std::size_t cd_count = 4;
  unsigned cd_values[4] = {0, 0, 0, 0};
  unsigned filter_config = 0;
  ASSERT_GE(H5Pget_filter_by_id2(dcpl.get(), H5Z_FILTER_DEFLATE, &flags, &cd_count, cd_values, 0,
                                 nullptr, &filter_config),
            0)
      << "no deflate filter";
  ASSERT_GE(cd_count, 1u);
  EXPECT_EQ(cd_values[0], 4u);  // compression level
  H5Eclear2(H5E_DEFAULT);
}

TEST(RunFileFrames, ThreeFramesReadBackExactly) {
  const auto dir = scratch_dir("frames");
  const double times[3] = {0.0, 0.125, 1.0 / 3.0};
  const std::uint64_t steps[3] = {0, 100, 18446744073709551615ULL};
  {
    RunFile run(dir, "scene", {});
    EXPECT_EQ(run.frame_count(), 0u);
    for (int f = 0; f < 3; ++f) {
      const std::vector<double> xy = positions(f);
      const std::vector<double> r = radii(f);
      run.write_frame(times[f], steps[f], kFrameParticles, {{"position", 2, xy}, {"radius", 1, r}});
      EXPECT_EQ(run.frame_count(), static_cast<std::size_t>(f + 1));
    }
    run.close();
    EXPECT_EQ(run.frame_count(), 3u);
  }
  h5::Handle file = open_read_only(dir / "run.h5");
  for (int f = 0; f < 3; ++f) {
    const std::string group = "/frames/00000" + std::to_string(f);
    SCOPED_TRACE(group);
    EXPECT_EQ(read_doubles(file.get(), group + "/position"), positions(f));
    EXPECT_EQ(read_doubles(file.get(), group + "/radius"), radii(f));
    EXPECT_EQ(dataset_dims(file.get(), group + "/position"),
              (std::vector<hsize_t>{kFrameParticles, 2}));
    EXPECT_EQ(dataset_dims(file.get(), group + "/radius"), (std::vector<hsize_t>{kFrameParticles}));
    h5::Handle g = h5::group(H5Gopen2(file.get(), group.c_str(), H5P_DEFAULT), group, "open");
    EXPECT_EQ(read_double_attribute(g.get(), "time_s"), times[f]);
    EXPECT_EQ(read_u64_attribute(g.get(), "step"), steps[f]);
    expect_chunked_deflate(file.get(), group + "/position", {kFrameParticles, 2});
    expect_chunked_deflate(file.get(), group + "/radius", {kFrameParticles});
  }
  EXPECT_EQ(H5Lexists(file.get(), "/frames/000003", H5P_DEFAULT), 0);
}

TEST(RunFileFrames, EmptyFrameHasAttributesButNoDatasets) {
  const auto dir = scratch_dir("frames_empty");
  {
    RunFile run(dir, "scene", {});
    run.write_frame(2.5, 7, 0, {{"position", 2, {}}, {"radius", 1, {}}});
    EXPECT_EQ(run.frame_count(), 1u);
  }
  h5::Handle file = open_read_only(dir / "run.h5");
  h5::Handle g = h5::group(H5Gopen2(file.get(), "/frames/000000", H5P_DEFAULT), "g", "open");
  EXPECT_EQ(read_double_attribute(g.get(), "time_s"), 2.5);
  EXPECT_EQ(read_u64_attribute(g.get(), "step"), 7u);
  H5G_info_t info{};
  ASSERT_GE(H5Gget_info(g.get(), &info), 0);
  EXPECT_EQ(info.nlinks, 0u);
}

TEST(RunFileFrames, LargeFrameIsCompressedInSensibleChunks) {
  const auto dir = scratch_dir("frames_large");
  constexpr std::size_t n = 200000;
  std::vector<double> xy(2 * n), v(2 * n), r(n, 0.002);
  for (std::size_t i = 0; i < n; ++i) {
    xy[2 * i] = static_cast<double>(i % 1000) * 1e-3;
    xy[2 * i + 1] = static_cast<double>(i / 1000) * 1e-3;
    v[2 * i] = 0.0;
    v[2 * i + 1] = -1.0;
  }
  {
    RunFile run(dir, "scene", {});
    run.write_frame(0.0, 0, n, {{"position", 2, xy}, {"velocity", 2, v}, {"radius", 1, r}});
  }
  h5::Handle file = open_read_only(dir / "run.h5");
  EXPECT_EQ(read_doubles(file.get(), "/frames/000000/position"), xy);
  EXPECT_EQ(read_doubles(file.get(), "/frames/000000/velocity"), v);
  expect_chunked_deflate(file.get(), "/frames/000000/position", {32768, 2});
  expect_chunked_deflate(file.get(), "/frames/000000/radius", {65536});
  h5::Handle dset = h5::dataset(H5Dopen2(file.get(), "/frames/000000/radius", H5P_DEFAULT), "r",
                                "open");
  EXPECT_LT(H5Dget_storage_size(dset.get()), n * sizeof(double) / 10);  // constant: compresses

  EXPECT_EQ(frame_chunk_rows(1, 1), 1u);
  EXPECT_EQ(frame_chunk_rows(1, 2), 1u);
  EXPECT_EQ(frame_chunk_rows(1000000, 1), 65536u);
  EXPECT_EQ(frame_chunk_rows(1000000, 2), 32768u);
}

TEST(RunFileFrames, MalformedFramesAreRejectedAndLeaveNoGroup) {
  const auto dir = scratch_dir("frames_bad");
  const std::vector<double> xy = positions(0);
  const std::vector<double> r = radii(0);
  {
    RunFile run(dir, "scene", {});
    EXPECT_THROW(run.write_frame(0, 0, kFrameParticles, {{"radius", 1, r}}), std::invalid_argument);
    EXPECT_THROW(run.write_frame(0, 0, kFrameParticles, {{"position", 1, r}}),
                 std::invalid_argument);
    EXPECT_THROW(run.write_frame(0, 0, kFrameParticles, {{"position", 2, xy}, {"radius", 1, xy}}),
                 std::invalid_argument);
    EXPECT_THROW(run.write_frame(0, 0, kFrameParticles, {{"position", 2, xy}, {"stress", 3, {}}}),
                 std::invalid_argument);
    EXPECT_THROW(run.write_frame(0, 0, kFrameParticles, {{"position", 2, xy}, {"a/b", 1, r}}),
                 std::invalid_argument);
    EXPECT_THROW(run.write_frame(0, 0, kFrameParticles, {{"position", 2, xy}, {"position", 2, xy}}),
                 std::invalid_argument);
    EXPECT_THROW(run.write_frame(NAN, 0, kFrameParticles, {{"position", 2, xy}}),
                 std::invalid_argument);
    EXPECT_EQ(run.frame_count(), 0u);
    run.write_frame(1.0, 1, kFrameParticles, {{"position", 2, xy}});
    EXPECT_EQ(run.frame_count(), 1u);
    run.close();
    EXPECT_THROW(run.write_frame(2.0, 2, kFrameParticles, {{"position", 2, xy}}), std::logic_error);
  }
  h5::Handle file = open_read_only(dir / "run.h5");
  EXPECT_EQ(read_doubles(file.get(), "/frames/000000/position"), xy);
  EXPECT_EQ(H5Lexists(file.get(), "/frames/000001", H5P_DEFAULT), 0);
}

}  // namespace
}  // namespace rockcut::coupler::testing
