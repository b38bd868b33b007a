// How the coupler's module processes wait when idle (coupler/process/module_environment.hpp).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <optional>
#include <string>

#include "process/module_environment.hpp"

namespace rockcut::coupler {
namespace {

std::optional<std::string> env(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::optional<std::string>(v) : std::nullopt;
}

// Each case from a clean environment; the test's own settings put back afterwards.
class ModuleEnvironment : public ::testing::Test {
 protected:
  void SetUp() override {
    policy_ = env("OMP_WAIT_POLICY");
    spin_ = env("GOMP_SPINCOUNT");
    clear();
  }
  void TearDown() override {
    clear();
    if (policy_) setenv("OMP_WAIT_POLICY", policy_->c_str(), 1);
    if (spin_) setenv("GOMP_SPINCOUNT", spin_->c_str(), 1);
  }
  static void clear() {
    unsetenv("OMP_WAIT_POLICY");
    unsetenv("GOMP_SPINCOUNT");
  }
  std::optional<std::string> policy_, spin_;
};

TEST_F(ModuleEnvironment, FollowsHowTheModulesShareTheCores) {
  prepare_module_environment(/*coupled=*/false, false);  // the DEM alone: libgomp's default
  EXPECT_FALSE(env("OMP_WAIT_POLICY"));
  EXPECT_FALSE(env("GOMP_SPINCOUNT"));
  prepare_module_environment(true, /*modules_take_turns=*/true);  // a short spin
  EXPECT_EQ(env("GOMP_SPINCOUNT"), std::string(kTurnsSpinCount));
  EXPECT_FALSE(env("OMP_WAIT_POLICY"));
  clear();
  prepare_module_environment(true, false);  // two teams at once: sleep at once
  EXPECT_EQ(env("OMP_WAIT_POLICY"), "PASSIVE");
  EXPECT_FALSE(env("GOMP_SPINCOUNT"));
}

TEST_F(ModuleEnvironment, TheUsersSettingWins) {
  setenv("OMP_WAIT_POLICY", "ACTIVE", 1);
  prepare_module_environment(true, true);
  EXPECT_EQ(env("OMP_WAIT_POLICY"), "ACTIVE");
  EXPECT_FALSE(env("GOMP_SPINCOUNT"));
  clear();
  setenv("GOMP_SPINCOUNT", "10", 1);
  prepare_module_environment(true, false);
  EXPECT_EQ(env("GOMP_SPINCOUNT"), "10");
  EXPECT_FALSE(env("OMP_WAIT_POLICY"));
}

}  // namespace
}  // namespace rockcut::coupler
