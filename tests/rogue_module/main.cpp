// rogue_module: the real DEM module with one fault in its replies, chosen by the environment's
// ROCKCUT_ROGUE_MODE. The integration tests run scenes with it (dem.executable) to check that the
// coupler refuses each fault with a ModuleFailure naming the module instead of crashing or looping:
//   nan_limit           InitReply with a stability limit that is NaN
//   nan_time            StepReports whose time is NaN
//   repeat_step         StepReports that repeat step 0
//   frame_fewer_arrays  Frames without arrays
//   frame_wrong_count   Frames with two particles' values
// and one that is no fault, to follow what the fluid is told of the solid through the coupler:
//   heavy_grains        InitReply.solid with 4 times the grain density
#include <cmath>
#include <cstdlib>
#include <string>

#include "service/dem_service.hpp"
#include "wire/module_main.hpp"

namespace {

class Rogue final : public rockcut::wire::ModuleHandler {
 public:
  explicit Rogue(std::string mode) : mode_(std::move(mode)) {}
  rockcut::wire::ModuleKind kind() const override { return real_.kind(); }
  std::string name() const override { return real_.name(); }
  std::string version() const override { return real_.version(); }
  std::vector<std::string> models() const override { return real_.models(); }
  void after_reply() override { real_.after_reply(); }

  void handle(const rockcut::wire::Message& request, rockcut::wire::Message& reply) override {
    real_.handle(request, reply);
    auto& e = reply.envelope;
    if (mode_ == "heavy_grains" && e.has_init_reply()) {
      auto* solid = e.mutable_init_reply()->mutable_solid();
      solid->set_grain_density_kg_m3(4.0 * solid->grain_density_kg_m3());
    } else if (mode_ == "nan_limit" && e.has_init_reply()) {
      e.mutable_init_reply()->add_limits()->set_dt_max_s(NAN);
    } else if (mode_ == "nan_time" && e.has_step_report() && e.step_report().step() > 0) {
      e.mutable_step_report()->set_time_s(NAN);
    } else if (mode_ == "repeat_step" && e.has_step_report()) {
      e.mutable_step_report()->set_step(0);
    } else if (mode_ == "frame_huge_count" && e.has_frame() && e.frame().time_s() > 0) {
      // A header that claims 2^61 rows for the values sent: count * components * 8 wraps.
      for (auto& h : *e.mutable_arrays()) h.set_count(std::uint64_t{1} << 61);
    } else if (mode_.starts_with("frame_") && e.has_frame() && e.frame().time_s() > 0) {
      const double t = e.frame().time_s();
      std::vector<std::pair<std::string, std::uint32_t>> arrays;
      for (const auto& h : e.arrays()) arrays.emplace_back(h.name(), h.components());
      reply.clear();
      reply.envelope.mutable_frame()->set_time_s(t);
      if (mode_ == "frame_wrong_count") {
        for (const auto& [name, components] : arrays) {
          const std::vector<double> two(2 * components, 1.0);
          reply.add_array(name, two, components);
        }
      }
    }
  }

 private:
  rockcut::dem::DemService real_;
  std::string mode_;
};

}  // namespace

int main(int argc, char** argv) {
  const char* mode = std::getenv("ROCKCUT_ROGUE_MODE");
  Rogue handler(mode ? mode : "");
  return rockcut::wire::module_main(argc, argv, handler);
}
