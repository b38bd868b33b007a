// The coupler does not trust its modules' replies: each fault of rogue_module (tests/rogue_module)
// ends the run cleanly, naming the module.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <string>
#include <utility>
#include <vector>

#include "integration/process_helpers.hpp"

namespace rockcut::test {
namespace {

namespace fs = std::filesystem;

// The coupler does not trust its modules: each fault of rogue_module (tests/rogue_module) ends
// the run with exit 3 and one line naming the module, never a signal or an endless loop.
TEST(UntrustedReplies, EachFaultIsAModuleFailureNamingTheModule) {
  const std::vector<std::pair<std::string, std::string>> faults = {
      {"nan_limit", "stability limit"},
      {"nan_time", "reported the time nan"},
      {"repeat_step", "reported step 0 after"},
      {"frame_fewer_arrays", "Frame without a valid"},
      {"frame_wrong_count", "has 2 rows, expected 900"},
      {"frame_huge_count", "2305843009213693952"},
  };
  for (const auto& [mode, expected] : faults) {
    const fs::path dir = fresh_dir("rogue_" + mode);
    setenv("ROCKCUT_ROGUE_MODE", mode.c_str(), 1);
    std::string out, err;
    const int code = run({bin("coupler"), "run", source("cases/verification/free_fall.pbtxt"),
                          "--out", (dir / "out").string(), "--set",
                          "dem.executable=" + std::string(ROCKCUT_BIN_DIR) + "/../tests/rogue_module"},
                         dir, "coupler", &out, &err, std::chrono::milliseconds(30000));
    unsetenv("ROCKCUT_ROGUE_MODE");
    EXPECT_EQ(code, 3) << mode << ": " << err;
    EXPECT_NE(err.find("rogue_module (pid"), std::string::npos) << mode << ": " << err;
    EXPECT_NE(err.find(expected), std::string::npos) << mode << ": " << err;
  }
}

}  // namespace
}  // namespace rockcut::test
