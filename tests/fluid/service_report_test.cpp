// The fluid module's protocol handler answers the model's scalars and the pressure nodes only at
// the exchanges the coupler records (FluidStep.report): at the others nothing would read them,
// and each node is a pass over every particle.
#include <gtest/gtest.h>

#include <string>
#include <vector>

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

}  // namespace
}  // namespace rockcut::fluid::test
