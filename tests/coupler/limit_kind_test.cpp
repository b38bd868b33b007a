// The coupler picks a stability limit by what it bounds (StabilityLimit.kind in the protocol),
// never by its display name: the expected coupling-lag error is read against the pore-fluid
// stiffness limit, whatever a fluid module calls it.
#include <gtest/gtest.h>

#include "run/time_plan.hpp"

namespace rockcut::coupler {
namespace {

Limit limit(std::string name, double dt_max_s, wire::LimitKind kind) {
  Limit l;
  l.module = "fluid_module";
  l.name = std::move(name);
  l.dt_max_s = dt_max_s;
  l.kind = kind;
  return l;
}

TEST(LimitKind, TheStiffnessLimitIsPickedByItsKindNotItsName) {
  // The old name with no kind is just a limit; a renamed one of the right kind is the one.
  const std::vector<Limit> limits = {
      limit("explicit_diffusion", 3e-6, wire::LIMIT_KIND_FLUID_DIFFUSION),
      limit("pore_fluid_stiffness", 1e-6, wire::LIMIT_KIND_UNSPECIFIED),
      limit("lagged force (stiffness)", 2e-6, wire::LIMIT_KIND_PORE_FLUID_STIFFNESS)};
  EXPECT_EQ(pore_fluid_stiffness_limit_s(limits), 2e-6);
}

TEST(LimitKind, TheSceneKeepsTheStiffnessLimitOfTheWayItAppliesTheForce) {
  const std::vector<Limit> limits = {
      limit("explicit_diffusion", 3e-6, wire::LIMIT_KIND_FLUID_DIFFUSION),
      limit("pore_fluid_stiffness", 1e-6, wire::LIMIT_KIND_PORE_FLUID_STIFFNESS),
      limit("pore_fluid_stiffness_extrapolated", 2e-6,
            wire::LIMIT_KIND_PORE_FLUID_STIFFNESS_EXTRAPOLATED)};
  rockcut::Scene scene;
  std::vector<Limit> kept = applicable_fluid_limits(scene, limits);  // "held" by default
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[1].name, "pore_fluid_stiffness");
  EXPECT_EQ(pore_fluid_stiffness_limit_s(kept), 1e-6);
  scene.mutable_coupling()->set_fluid_force("extrapolated");
  kept = applicable_fluid_limits(scene, limits);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].name, "explicit_diffusion");
  EXPECT_EQ(pore_fluid_stiffness_limit_s(kept), 2e-6);
}

TEST(LimitKind, NoStiffnessLimitIsZero) {
  EXPECT_EQ(pore_fluid_stiffness_limit_s({}), 0.0);
  EXPECT_EQ(pore_fluid_stiffness_limit_s({limit("pore_fluid_stiffness", 1e-6,
                                                wire::LIMIT_KIND_UNSPECIFIED)}),
            0.0);
}

}  // namespace
}  // namespace rockcut::coupler
