// The checkpoint file (coupler/checkpoint/checkpoint_file.hpp): what is written is read back bit for
// bit, any change to its contents is caught by the checksum, and pruning keeps the newest.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <cstring>
#include <iterator>

#include "checkpoint/checkpoint_file.hpp"

namespace rockcut::coupler {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(ROCKCUT_TEST_TMP) / "checkpoint_file" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Checkpoint sample(std::uint64_t step) {
  Checkpoint c;
  c.rockcut_version = "1.2.3";
  c.protocol_version = 3;
  c.scene_text = "title: \"x\"\ntime { end_time_s: 1 }\n";
  c.scene_path = "/cases/x.pbtxt";
  c.overrides = {"time.end_time_s=1", "dem.threads=2"};
  c.step = step;
  c.time_s = 0.1 * static_cast<double>(step);
  state::StateArchive& dem = c.parts["dem"];
  // Values whose bits a text or float round trip would lose.
  dem.put("position_m", std::vector<double>{0.1, -0.0, std::nextafter(1.0, 2.0), 1e-310,
                                            std::numeric_limits<double>::quiet_NaN(), 3.0},
          2);
  dem.put("empty", std::vector<double>{});
  dem.put_text("note", "line one\nline two");
  c.parts["coupler"].put_scalar("steps", static_cast<double>(step));
  return c;
}

TEST(CheckpointFile, RoundTripKeepsEveryBit) {
  const fs::path dir = fresh("round_trip");
  const Checkpoint c = sample(42);
  const fs::path file = write_checkpoint(dir, c);
  EXPECT_EQ(file.filename(), "checkpoint_000000000042.h5");
  const Checkpoint r = read_checkpoint(file);
  EXPECT_EQ(r.rockcut_version, c.rockcut_version);
  EXPECT_EQ(r.protocol_version, c.protocol_version);
  EXPECT_EQ(r.scene_text, c.scene_text);
  EXPECT_EQ(r.scene_path, c.scene_path);
  EXPECT_EQ(r.overrides, c.overrides);
  EXPECT_EQ(r.step, 42u);
  EXPECT_EQ(r.time_s, c.time_s);
  ASSERT_EQ(r.parts.size(), 2u);
  const auto& a = c.parts.at("dem").array("position_m");
  const auto& b = r.parts.at("dem").array("position_m");
  EXPECT_EQ(b.components, 2u);
  ASSERT_EQ(a.values.size(), b.values.size());
  EXPECT_EQ(std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(double)), 0);
  EXPECT_TRUE(r.parts.at("dem").values("empty").empty());
  EXPECT_EQ(r.parts.at("dem").text("note"), "line one\nline two");
  EXPECT_EQ(checkpoint_checksum(r), checkpoint_checksum(c));
  // Nothing but the checkpoint is left in the directory (the temporary file was renamed).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(CheckpointFile, ChecksumCatchesAnyChangedValue) {
  Checkpoint c = sample(1);
  const std::uint64_t sum = checkpoint_checksum(c);
  Checkpoint d = c;
  d.parts["dem"].put("position_m", std::vector<double>{0.1, 0.0, 1.0, 1e-310, 0.0, 3.0}, 2);
  EXPECT_NE(checkpoint_checksum(d), sum);
  d = c;
  d.scene_text += " ";
  EXPECT_NE(checkpoint_checksum(d), sum);
  d = c;
  d.step = 2;
  EXPECT_NE(checkpoint_checksum(d), sum);
}

TEST(CheckpointFile, DamagedFilesAreRefusedWithAReason) {
  const fs::path dir = fresh("damaged");
  const fs::path file = write_checkpoint(dir, sample(7));
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  // Truncated: not readable.
  std::ofstream(dir / "truncated.h5", std::ios::binary) << bytes.substr(0, bytes.size() / 3);
  EXPECT_THROW(read_checkpoint(dir / "truncated.h5"), CheckpointError);
  // Not HDF5 at all.
  std::ofstream(dir / "text.h5") << "not a checkpoint\n";
  try {
    read_checkpoint(dir / "text.h5");
    FAIL() << "a text file was read as a checkpoint";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("not a readable HDF5 file"), std::string::npos);
  }
  // One bit of the position data flipped (found by its bytes): the checksum says so.
  const double marker = std::nextafter(1.0, 2.0);
  const std::string needle(reinterpret_cast<const char*>(&marker), sizeof marker);
  const std::size_t at = bytes.find(needle);
  ASSERT_NE(at, std::string::npos);
  bytes[at] ^= 0x01;
  std::ofstream(dir / "flipped.h5", std::ios::binary) << bytes;
  try {
    read_checkpoint(dir / "flipped.h5");
    FAIL() << "a corrupted checkpoint was accepted";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("checksum mismatch"), std::string::npos) << e.what();
  }
}

TEST(CheckpointFile, PruneKeepsTheNewestAndListsNewestFirst) {
  const fs::path dir = fresh("prune");
  for (std::uint64_t step : {5u, 100u, 20u, 1000u}) write_checkpoint(dir, sample(step));
  std::ofstream(dir / ".checkpoint_000000000001.h5.tmp") << "left by a killed writer";
  prune_checkpoints(dir, 2);
  const auto left = list_checkpoints(dir);
  ASSERT_EQ(left.size(), 2u);
  EXPECT_EQ(left[0].filename(), "checkpoint_000000001000.h5");
  EXPECT_EQ(left[1].filename(), "checkpoint_000000000100.h5");
  EXPECT_FALSE(fs::exists(dir / ".checkpoint_000000000001.h5.tmp"));
  EXPECT_TRUE(list_checkpoints(dir / "missing").empty());
}

}  // namespace
}  // namespace rockcut::coupler

namespace rockcut::coupler {
namespace {

// Temporary files follow no link: a link planted at the checkpoint's temporary name, or at
// summary.json's or run.xdmf's, is replaced by a fresh file and its target is left alone; a
// checkpoints/ folder that is itself a link is refused.
TEST(CheckpointFile, TemporaryFilesFollowNoPlantedLink) {
  const fs::path dir = fresh("planted_links");
  const fs::path victim = dir / "victim.txt";
  std::ofstream(victim) << "not yours";
  const fs::path checkpoints = dir / "checkpoints";
  fs::create_directories(checkpoints);
  fs::create_symlink(victim, checkpoints / ".checkpoint_000000000007.h5.tmp");
  const fs::path written = write_checkpoint(checkpoints, sample(7));
  EXPECT_EQ(read_checkpoint(written).step, 7u);
  std::ifstream in(victim);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "not yours");
  EXPECT_FALSE(fs::exists(checkpoints / ".checkpoint_000000000007.h5.tmp"));

  // The folder itself a link to another directory: refused, nothing written there.
  const fs::path elsewhere = dir / "elsewhere";
  fs::create_directories(elsewhere);
  fs::create_symlink(elsewhere, dir / "linked_checkpoints");
  EXPECT_THROW(write_checkpoint(dir / "linked_checkpoints", sample(8)), std::runtime_error);
  EXPECT_TRUE(fs::is_empty(elsewhere));
}

}  // namespace
}  // namespace rockcut::coupler
