// The fluid module's protocol handler answers the model's scalars and the pressure nodes only at
// the exchanges the coupler records (FluidStep.report): at the others nothing would read them,
// and each node is a pass over every particle. It derives the displacement a model needs from
// successive positions instead of asking the DEM for it.
#include <gtest/gtest.h>

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
  *init.envelope.mutable_init()->mutable_scene() =
      scene::load_scene(std::string(ROCKCUT_SOURCE_DIR) + "/cases/cutting/saturated_reduced.pbtxt").scene;
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
  const rockcut::Scene scene =
      scene::load_scene(std::string(ROCKCUT_SOURCE_DIR) + "/cases/cutting/saturated_reduced.pbtxt").scene;
  std::unique_ptr<FluidModel> direct = make_model(scene);
  const std::vector<std::string> model_needs = direct->needs();
  ASSERT_NE(std::find(model_needs.begin(), model_needs.end(), "displacement"), model_needs.end());
  direct->initialise({lattice.radius, lattice.position});

  FluidService service;
  wire::Message init, reply;
  *init.envelope.mutable_init()->mutable_scene() = scene;
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

}  // namespace
}  // namespace rockcut::fluid::test
