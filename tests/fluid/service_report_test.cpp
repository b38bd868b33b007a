// The fluid module's protocol handler answers the model's scalars and the pressure nodes only at
// the exchanges the coupler records (FluidStep.report): at the others nothing would read them,
// and each node is a pass over every particle. It derives the displacement a model needs from
// successive positions instead of asking the DEM for it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <algorithm>
#include <cstring>

#include "models/registry.hpp"
#include "scene/scene_loader.hpp"
#include "service/fluid_service.hpp"
#include "wire/protocol.hpp"

namespace rockcut::fluid::test {
namespace {

// The fluid's part of `scene` (what the coupler sends in Init), with the solid properties a DEM of
// that scene reports (dem_module/service/dem_setup.cpp, solid_properties).
wire::FluidConfig fluid_config(const rockcut::Scene& scene) {
  wire::FluidConfig config;
  *config.mutable_fluid() = scene.fluid();
  config.set_water_depth_m(scene.water_depth_m());
  wire::SolidProperties* solid = config.mutable_solid();
  solid->set_grain_density_kg_m3(scene.dem().density_kg_m3());
  solid->set_local_damping(scene.dem().damping().local_coefficient());
  solid->set_dynamic(!scene.dem().has_prescribed_motion());
  solid->set_seals_at_walls(scene.dem().walls_size() > 0 || scene.dem().has_tool());
  return config;
}

rockcut::Scene saturated_reduced() {
  return scene::load_scene(std::string(ROCKCUT_SOURCE_DIR) + "/cases/cutting/saturated_reduced.pbtxt")
      .scene;
}

// A 20 x 10 lattice of 1.2 mm discs with the reduced saturated scene's fluid (h 6 mm).
struct Lattice {
  std::vector<double> radius, position;
  Lattice() {
    for (int row = 0; row < 10; ++row) {
      for (int col = 0; col < 20; ++col) {
        radius.push_back(0.0012);
        position.push_back(0.0024 * col);
        position.push_back(0.0024 * row);
      }
    }
  }
};

wire::Message step_request(double dt_s, bool report) {
  wire::Message m;
  wire::FluidStep* s = m.envelope.mutable_fluid_step();
  s->set_dt_s(dt_s);
  s->set_time_s(dt_s);
  s->set_report(report);
  wire::Probe* p = s->add_probes();
  p->set_name("p1");
  p->set_x_min_m(-1.0);
  p->set_y_min_m(-1.0);
  p->set_x_max_m(1.0);
  p->set_y_max_m(1.0);
  return m;
}

TEST(FluidService, AnswersScalarsAndPressureNodesOnlyWhenAskedToReport) {
  const Lattice lattice;
  const std::size_t n = lattice.radius.size();
  FluidService service;
  wire::Message init, reply;
  *init.envelope.mutable_init()->mutable_fluid() = fluid_config(saturated_reduced());
  init.add_array(wire::field::kRadius, lattice.radius, 1);
  init.add_array(wire::field::kPosition, lattice.position, 2);
  service.handle(init, reply);
  ASSERT_TRUE(reply.envelope.has_init_reply());
  std::vector<std::string> needs(reply.envelope.init_reply().needs().begin(),
                                 reply.envelope.init_reply().needs().end());

  // Position first (the lattice), then the rest of what the model needs at rest.
  auto request = [&](double dt_s, bool report) {
    wire::Message m = step_request(dt_s, report);
    for (const std::string& f : needs) {
      if (f == wire::field::kPosition) {
        m.add_array(f, lattice.position, 2);
      } else if (f == wire::field::kWallSegments) {
        m.add_array(f, std::vector<double>{}, 4);
      } else {
        m.add_array(f, std::vector<double>(2 * n, 0.0), 2);
      }
    }
    return m;
  };

  wire::Message answer;
  service.handle(request(1e-7, false), answer);
  ASSERT_TRUE(answer.envelope.has_fluid_result());
  EXPECT_TRUE(answer.envelope.fluid_result().scalars().empty());
  EXPECT_EQ(answer.array(wire::field::kForce, 2).size(), 2 * n);  // the force always comes

  service.handle(request(1e-7, true), answer);
  const auto& scalars = answer.envelope.fluid_result().scalars();
  EXPECT_TRUE(scalars.contains("pressure_max_pa"));
  ASSERT_TRUE(scalars.contains("probe_p1_particles"));
  EXPECT_EQ(scalars.at("probe_p1_particles"), static_cast<double>(n));  // the box holds them all
  EXPECT_EQ(answer.array(wire::field::kForce, 2).size(), 2 * n);
}

// The SP model takes its strain from the displacement since the last exchange. The service asks
// the coupler for positions only and subtracts the last exchange's (Init's at first), which is
// the DEM's own subtraction (dem_service.cpp, "displacement"): the forces must equal, bit for bit,
// those of the model handed the displacement directly, over steps that compress the lattice.
TEST(FluidService, DerivesTheDisplacementFromSuccessivePositions) {
  const Lattice lattice;
  const std::size_t n = lattice.radius.size();
  const wire::FluidConfig config = fluid_config(saturated_reduced());
  std::unique_ptr<FluidModel> direct = make_model(config);
  const std::vector<std::string> model_needs = direct->needs();
  ASSERT_NE(std::find(model_needs.begin(), model_needs.end(), "displacement"), model_needs.end());
  direct->initialise({lattice.radius, lattice.position});

  FluidService service;
  wire::Message init, reply;
  *init.envelope.mutable_init()->mutable_fluid() = config;
  init.add_array(wire::field::kRadius, lattice.radius, 1);
  init.add_array(wire::field::kPosition, lattice.position, 2);
  service.handle(init, reply);
  const auto& needs = reply.envelope.init_reply().needs();
  EXPECT_EQ(std::count(needs.begin(), needs.end(), "displacement"), 0);  // not on the wire
  ASSERT_EQ(std::count(needs.begin(), needs.end(), "position"), 1);

  // Three exchanges: the lattice squeezed towards its centre row by a growing, uneven amount.
  std::vector<double> previous = lattice.position, position(2 * n), displacement(2 * n);
  std::vector<double> force(2 * n);
  const double dt_s = 1e-7;
  for (int exchange = 1; exchange <= 3; ++exchange) {
    for (std::size_t i = 0; i < n; ++i) {
      const double y0 = lattice.position[2 * i + 1];
      position[2 * i] = lattice.position[2 * i] * (1.0 - 1e-5 * exchange * exchange);
      position[2 * i + 1] = y0 - 3e-5 * exchange * (y0 - 0.0108) * (1.0 + 0.1 * (i % 7));
    }
    for (std::size_t k = 0; k < 2 * n; ++k) displacement[k] = position[k] - previous[k];
    previous = position;
    direct->step(dt_s, exchange * dt_s, {position, {}, displacement, {}}, force);

    wire::Message request = step_request(dt_s, false);
    for (const std::string& f : needs) {
      if (f == wire::field::kPosition) {
        request.add_array(f, position, 2);
      } else {
        ASSERT_EQ(f, wire::field::kWallSegments);
        request.add_array(f, std::vector<double>{}, 4);
      }
    }
    wire::Message answer;
    service.handle(request, answer);
    const auto got = answer.array(wire::field::kForce, 2);
    ASSERT_EQ(got.size(), force.size());
    EXPECT_EQ(std::memcmp(got.data(), force.data(), force.size() * sizeof(double)), 0)
        << "exchange " << exchange;
    const double largest = std::abs(*std::max_element(
        force.begin(), force.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }));
    EXPECT_GT(largest, 0.0) << "the squeeze must load the pore fluid, or the test shows nothing";
  }
}

// The InitReply of a FluidService given `config` and the lattice, or the Error's text.
struct InitAnswer {
  wire::InitReply reply;
  std::string error;
};
InitAnswer init_with(const wire::Init& init) {
  const Lattice lattice;
  FluidService service;
  wire::Message request, reply;
  *request.envelope.mutable_init() = init;
  request.add_array(wire::field::kRadius, lattice.radius, 1);
  request.add_array(wire::field::kPosition, lattice.position, 2);
  try {
    service.handle(request, reply);
  } catch (const std::exception& e) {
    return {{}, e.what()};
  }
  return {reply.envelope.init_reply(), ""};
}
InitAnswer init_with(const wire::FluidConfig& config) {
  wire::Init init;
  *init.mutable_fluid() = config;
  return init_with(init);
}

// The pore-fluid stiffness limit of an InitReply, found by its kind (held, or with the
// extrapolated force); -1 when there is none.
double stiffness_limit_s(const wire::InitReply& reply,
                         wire::LimitKind kind = wire::LIMIT_KIND_PORE_FLUID_STIFFNESS) {
  double dt_s = -1.0;
  for (const wire::StabilityLimit& l : reply.limits()) {
    if (l.kind() == kind) dt_s = l.dt_max_s();
  }
  return dt_s;
}

// The fluid takes only its own part of the scene: an Init with the DEM's part or none is refused
// with an error that says what is missing and where it belongs.
TEST(FluidService, RefusesAnInitWithoutItsPart) {
  wire::Init dem_only;
  dem_only.mutable_dem()->mutable_dem()->set_density_kg_m3(2650);
  const InitAnswer wrong = init_with(dem_only);
  EXPECT_NE(wrong.error.find("Init carries no fluid part (Init.fluid"), std::string::npos) << wrong.error;
  EXPECT_NE(wrong.error.find("it carries the DEM's part (Init.dem), which is for dem_module"),
            std::string::npos) << wrong.error;
  const InitAnswer empty = init_with(wire::Init{});
  EXPECT_NE(empty.error.find("Init carries no fluid part"), std::string::npos) << empty.error;
  EXPECT_EQ(empty.error.find("DEM's part"), std::string::npos) << empty.error;

  // Its part is validated with the scene's rules, named as in the scene file.
  wire::FluidConfig config = fluid_config(saturated_reduced());
  config.mutable_fluid()->set_threads(0);
  config.set_water_depth_m(-1.0);
  config.mutable_solid()->set_local_damping(1.5);
  config.mutable_solid()->set_grain_density_kg_m3(0.0);
  const InitAnswer bad = init_with(config);
  EXPECT_NE(bad.error.find("the fluid part of the scene sent in Init is not valid"), std::string::npos)
      << bad.error;
  EXPECT_NE(bad.error.find("fluid.threads = 0 is out of range"), std::string::npos) << bad.error;
  EXPECT_NE(bad.error.find("water_depth_m = -1 is out of range"), std::string::npos) << bad.error;
  EXPECT_NE(bad.error.find("solid.local_damping = 1.5 is out of range"), std::string::npos) << bad.error;
  EXPECT_NE(bad.error.find("solid.grain_density_kg_m3 = 0 is out of range"), std::string::npos)
      << bad.error;
  config = fluid_config(saturated_reduced());
  config.mutable_solid()->clear_grain_density_kg_m3();
  EXPECT_NE(init_with(config).error.find("missing required field \"solid.grain_density_kg_m3\""),
            std::string::npos);
  config = fluid_config(saturated_reduced());
  config.mutable_fluid()->clear_model();
  EXPECT_NE(init_with(config).error.find("missing required field \"fluid.model\""), std::string::npos);

  // The SP models need the solid's properties; without them the Init is refused, not guessed.
  config = fluid_config(saturated_reduced());
  config.clear_solid();
  const InitAnswer no_solid = init_with(config);
  EXPECT_NE(no_solid.error.find("needs the solid's properties (Init.fluid.solid"), std::string::npos)
      << no_solid.error;
}

// What the fluid knows of the solid arrives through the protocol (SolidProperties), and its
// pore-fluid stiffness limit C alpha_d sqrt(m_min / (alpha M)) follows it: 4 times the grain
// density doubles it, half the damping halves it, a prescribed (not dynamic) solid has none.
// Walls or a tool make the model ask for their segments. The ratios are exact up to the rounding
// of one square root and a few products (1e-14 relative).
TEST(FluidService, TakesTheSolidPropertiesFromTheProtocol) {
  const wire::FluidConfig base = fluid_config(saturated_reduced());
  ASSERT_TRUE(base.solid().dynamic());
  const InitAnswer reference = init_with(base);
  ASSERT_EQ(reference.error, "");
  const double dt0 = stiffness_limit_s(reference.reply);
  ASSERT_GT(dt0, 0.0);
  const auto& needs0 = reference.reply.needs();
  EXPECT_EQ(std::count(needs0.begin(), needs0.end(), wire::field::kWallSegments),
            base.solid().seals_at_walls() ? 1 : 0);

  wire::FluidConfig heavier = base;
  heavier.mutable_solid()->set_grain_density_kg_m3(4.0 * base.solid().grain_density_kg_m3());
  EXPECT_NEAR(stiffness_limit_s(init_with(heavier).reply) / dt0, 2.0, 1e-14);

  wire::FluidConfig less_damped = base;
  less_damped.mutable_solid()->set_local_damping(0.5 * base.solid().local_damping());
  EXPECT_NEAR(stiffness_limit_s(init_with(less_damped).reply) / dt0, 0.5, 1e-14);

  wire::FluidConfig prescribed = base;
  prescribed.mutable_solid()->set_dynamic(false);
  EXPECT_EQ(stiffness_limit_s(init_with(prescribed).reply), -1.0);

  wire::FluidConfig walls = base;
  walls.mutable_solid()->set_seals_at_walls(!base.solid().seals_at_walls());
  const InitAnswer flipped = init_with(walls);
  EXPECT_EQ(std::count(flipped.reply.needs().begin(), flipped.reply.needs().end(),
                       wire::field::kWallSegments),
            walls.solid().seals_at_walls() ? 1 : 0);

  // With the force extrapolated between exchanges the limit is C_x cbrt(dt_held m_min / k_n).
  // Under dashpots (zeta 0.1 on k_n 7.25 GPa, no local damping) it is above the held one; 8 times
  // the contact stiffness makes it 1/sqrt(2) times (dt_held goes as sqrt(k_n)), 4 times the
  // density 2 times (dt_held and m_min), and without contact stiffness it is the held one.
  constexpr auto kExtrapolated = wire::LIMIT_KIND_PORE_FLUID_STIFFNESS_EXTRAPOLATED;
  wire::FluidConfig dashpots = base;
  dashpots.mutable_solid()->set_local_damping(0.0);
  dashpots.mutable_solid()->set_viscous_damping_ratio(0.1);
  dashpots.mutable_solid()->set_normal_stiffness_pa(7.25e9);
  const InitAnswer viscous = init_with(dashpots);
  const double dx0 = stiffness_limit_s(viscous.reply, kExtrapolated);
  ASSERT_GT(dx0, stiffness_limit_s(viscous.reply));
  wire::FluidConfig stiffer = dashpots;
  stiffer.mutable_solid()->set_normal_stiffness_pa(8.0 * 7.25e9);
  EXPECT_NEAR(stiffness_limit_s(init_with(stiffer).reply, kExtrapolated) / dx0, std::sqrt(0.5),
              1e-14);
  wire::FluidConfig heavier_dashpots = dashpots;
  heavier_dashpots.mutable_solid()->set_grain_density_kg_m3(4.0 * base.solid().grain_density_kg_m3());
  EXPECT_NEAR(stiffness_limit_s(init_with(heavier_dashpots).reply, kExtrapolated) / dx0, 2.0, 1e-14);
  // Without local damping the cut's own damping, zeta_0 = 0.0095 (measured: docs/model.md), adds
  // to the dashpots' zeta: the limit's cube goes as zeta + zeta_0, so with no damping at all the
  // limit is cbrt(0.0095 / 0.1095) of zeta 0.1's and not nothing, at zeta 0.005 cbrt(0.0145 /
  // 0.1095) of it.
  wire::FluidConfig undamped = dashpots;
  undamped.mutable_solid()->set_viscous_damping_ratio(0.0);
  EXPECT_NEAR(stiffness_limit_s(init_with(undamped).reply, kExtrapolated) / dx0,
              std::cbrt(0.0095 / 0.1095), 1e-12);
  wire::FluidConfig light = dashpots;
  light.mutable_solid()->set_viscous_damping_ratio(0.005);
  EXPECT_NEAR(stiffness_limit_s(init_with(light).reply, kExtrapolated) / dx0,
              std::cbrt(0.0145 / 0.1095), 1e-12);
  // Under local damping (alpha_d 0.7, no dashpots) the line does worse than the held force.
  ASSERT_EQ(base.solid().viscous_damping_ratio(), 0.0);
  wire::FluidConfig local = base;
  local.mutable_solid()->set_normal_stiffness_pa(7.25e9);
  const InitAnswer local_answer = init_with(local);
  EXPECT_LT(stiffness_limit_s(local_answer.reply, kExtrapolated),
            stiffness_limit_s(local_answer.reply));
  wire::FluidConfig no_contacts = base;
  no_contacts.mutable_solid()->set_normal_stiffness_pa(0.0);
  EXPECT_EQ(stiffness_limit_s(init_with(no_contacts).reply, kExtrapolated), dt0);
  EXPECT_EQ(stiffness_limit_s(init_with(prescribed).reply, kExtrapolated), -1.0);

  // The diffusion limit is typed too.
  bool diffusion = false;
  for (const wire::StabilityLimit& l : reference.reply.limits()) {
    diffusion = diffusion || l.kind() == wire::LIMIT_KIND_FLUID_DIFFUSION;
  }
  EXPECT_TRUE(diffusion);
}

// On fewer points than grains (fluid.point_spacing) the stiffness limits stay those of the
// lightest grain, the diffusion limit is the points' (h grown by their spacing: about 4 times
// the limit at twice the spacing) and says on how many points; a spacing below 1 and the open
// water's drag, which acts on single grains, are refused by name.
TEST(FluidService, OnPointsKeepsTheGrainsStiffnessLimitsAndRefusesTheDrag) {
  const wire::FluidConfig base = fluid_config(saturated_reduced());
  const InitAnswer grains = init_with(base);
  ASSERT_EQ(grains.error, "");
  wire::FluidConfig points = base;
  points.mutable_fluid()->set_point_spacing(2.0);
  const InitAnswer on_points = init_with(points);
  ASSERT_EQ(on_points.error, "");
  EXPECT_EQ(stiffness_limit_s(on_points.reply), stiffness_limit_s(grains.reply));
  constexpr auto kDiffusion = wire::LIMIT_KIND_FLUID_DIFFUSION;
  const double ratio = stiffness_limit_s(on_points.reply, kDiffusion) /
                       stiffness_limit_s(grains.reply, kDiffusion);
  EXPECT_GT(ratio, 3.0);  // (h_points / h)^2 = grains / points: about 4, 3.7-4.2 on this lattice
  EXPECT_LT(ratio, 5.0);
  bool named = false;
  for (const wire::StabilityLimit& l : on_points.reply.limits()) {
    named = named || l.detail().find(" points for 200 grains") != std::string::npos;
  }
  EXPECT_TRUE(named);
  // The implicit model runs on points the same way.
  wire::FluidConfig implicit = points;
  implicit.mutable_fluid()->set_model("implicit");
  const InitAnswer implicit_points = init_with(implicit);
  ASSERT_EQ(implicit_points.error, "");
  EXPECT_EQ(implicit_points.reply.model(), "implicit");

  wire::FluidConfig below_one = base;
  below_one.mutable_fluid()->set_point_spacing(0.5);
  EXPECT_NE(init_with(below_one).error.find("fluid.point_spacing = 0.5 is out of range"),
            std::string::npos)
      << init_with(below_one).error;
  wire::FluidConfig drag = points;
  drag.mutable_fluid()->set_open_water_drag(true);
  const std::string error = init_with(drag).error;
  EXPECT_NE(error.find("fluid.open_water_drag acts on single grains and fluid.point_spacing"),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace rockcut::fluid::test
