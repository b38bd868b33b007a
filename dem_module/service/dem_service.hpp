// The DEM module's protocol handler: builds the DEM from the scene (service/dem_setup.hpp) and
// answers Advance / ApplyForces / FrameRequest with arrays copied straight from the particle
// arrays, and step reports with the tool force, breaks and the energy ledger.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "service/dem_setup.hpp"
#include "wire/module_server.hpp"

namespace rockcut::dem {

class DemService final : public wire::ModuleHandler {
 public:
  wire::ModuleKind kind() const override { return wire::MODULE_KIND_DEM; }
  std::string name() const override { return "dem_module"; }
  std::string version() const override;
  std::vector<std::string> models() const override { return {"dem"}; }
  void handle(const wire::Message& request, wire::Message& reply) override;
  void after_reply() override;
  void set_read_root(const std::filesystem::path& root) override { read_root_ = root; }

 private:
  void init(const wire::Init& init, wire::Message& reply);
  void subscribe(const wire::Subscribe& subscribe, wire::Message& reply);
  void advance(const wire::Message& request, wire::Message& reply);
  void apply_forces(const wire::Message& request, wire::Message& reply);
  /// Completes the pending split step with the request's "force" array (or, at t = 0, sets it).
  void hold_forces(const wire::Message& request);
  void frame(const wire::FrameRequest& request, wire::Message& reply);
  void add_field(std::string_view field, wire::Message& reply);
  void report(wire::Message& reply);
  /// Checkpoint and restart: the DEM's state (core/dem_state.cpp) and the service's own.
  void save_state(wire::Message& reply);
  void load_state(const wire::Message& request, wire::Message& reply);
  void report_rig(google::protobuf::Map<std::string, double>& out);
  /// Runs the runtime guards; a trip goes into the report and stops further Advances.
  void check_guards_into(double kinetic_energy_j, wire::StepReport& report);
  DemSystem& system();

  std::filesystem::path read_root_;  // empty: Init's scene directory alone bounds what is read
  DemSetup setup_;
  std::vector<std::string> send_fields_;      // per-step fields the fluid asked for
  std::vector<double> position_at_exchange_;  // for "displacement"
  std::vector<double> scratch_;
  std::vector<std::uint32_t> bond_count_;
  std::size_t breaks_sent_ = 0;               // breaks already handed out in frames
  double split_dt_s_ = 0.0;
  std::uint64_t guard_checked_step_ = 0;  // last step the guards ran on in a merged exchange
  std::string stopped_by_;        // the guard that stopped the time stepping, if any
};

}  // namespace rockcut::dem
