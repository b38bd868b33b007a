#include "service/dem_service.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "core/clusters.hpp"
#include "core/thread_advice.hpp"
#include "scene/particle_budget.hpp"
#include "scene/validation.hpp"
#include "wire/inproc_registry.hpp"
#include "wire/protocol.hpp"
#include "wire/state_message.hpp"

namespace rockcut::dem {

namespace {

// Guards inside a long Advance every this many steps: one pass over particles, bonds and contacts
// per 50 steps, about 1 % of the step cost.
constexpr unsigned kGuardEverySteps = 50;

// Fields this module can put on the wire: per particle, plus "breaks" (the bond breaks since the
// last request, as arrays break_time_s, break_position, break_mode with 0 tensile, 1 shear).
const std::vector<std::string_view> kProvided = {
    wire::field::kPosition, wire::field::kVelocity,      wire::field::kVelocityHalf,
    wire::field::kDisplacement, wire::field::kRadius,    wire::field::kForce,
    wire::field::kExternalForce, "angular_velocity",     "damage",
    wire::field::kWallSegments,  "breaks"};

}  // namespace

std::string DemService::version() const { return ROCKCUT_VERSION; }

DemSystem& DemService::system() {
  if (!setup_.system) throw std::logic_error("dem_module: request before Init");
  return *setup_.system;
}

void DemService::handle(const wire::Message& request, wire::Message& reply) {
  const wire::Envelope& e = request.envelope;
  switch (e.body_case()) {
    case wire::Envelope::kInit: return init(e.init(), reply);
    case wire::Envelope::kAdvance: return advance(request, reply);
    case wire::Envelope::kApplyForces: return apply_forces(request, reply);
    case wire::Envelope::kSubscribe: return subscribe(e.subscribe(), reply);
    case wire::Envelope::kFrameRequest: return frame(e.frame_request(), reply);
    case wire::Envelope::kSaveState: return save_state(reply);
    case wire::Envelope::kLoadState: return load_state(request, reply);
    default:
      throw std::invalid_argument("dem_module: unexpected request (envelope body " +
                                  std::to_string(e.body_case()) + ")");
  }
}

namespace {

// The packing file, if the scene names one, must be a regular file of bounded size in the scene's
// directory or below it (DemConfig.scene_dir, from the coupler): a peer cannot make the module
// read anything else. Over tcp that directory comes from the peer, so it must lie under the
// module's own read root (`--read-under`; empty: not bounded further). Returns the DEM's part with
// the file's path made canonical.
rockcut::Dem with_allowed_packing_file(const wire::DemConfig& config,
                                       const std::filesystem::path& read_root) {
  namespace fs = std::filesystem;
  rockcut::Dem dem = config.dem();
  if (!dem.has_packing_file()) return dem;
  const fs::path dir(config.scene_dir());
  if (dir.empty() || dir.is_relative()) {
    throw std::invalid_argument("dem.packing_file: Init names no absolute scene directory to "
                                "read it from");
  }
  std::error_code ec;
  const fs::path allowed = fs::canonical(dir, ec);
  if (ec) throw std::invalid_argument("dem.packing_file: the scene directory cannot be opened");
  if (!read_root.empty()) {
    const auto [end, _] = std::mismatch(read_root.begin(), read_root.end(), allowed.begin(),
                                        allowed.end());
    if (end != read_root.end()) {
      throw std::invalid_argument("dem.packing_file: the scene directory " + allowed.string() +
                                  " is outside the directory this module reads under (" +
                                  read_root.string() + "; dem_module --read-under DIR)");
    }
  }
  const fs::path named(dem.packing_file().path());
  // Where it leads (symbolic links followed) is checked before whether it exists: the module
  // tells nothing about files outside the directory.
  const fs::path file = fs::weakly_canonical(named.is_relative() ? allowed / named : named, ec);
  const auto [end, _] = std::mismatch(allowed.begin(), allowed.end(), file.begin(), file.end());
  if (ec || end != allowed.end()) {
    throw std::invalid_argument("dem.packing_file \"" + named.string() +
                                "\": outside the scene's directory " + allowed.string() +
                                " (a module reads files only there and below)");
  }
  if (!fs::exists(file, ec)) {
    throw std::invalid_argument("dem.packing_file \"" + named.string() +
                                "\": cannot open packing file");
  }
  if (!fs::is_regular_file(file, ec)) {
    throw std::invalid_argument("dem.packing_file \"" + named.string() + "\": not a regular file");
  }
  const auto bytes = fs::file_size(file, ec);
  if (ec || bytes > scene::kMaxPackingFileBytes) {
    throw std::invalid_argument("dem.packing_file \"" + named.string() + "\": larger than " +
                                std::to_string(scene::kMaxPackingFileBytes >> 20) +
                                " MiB (at most " + std::to_string(scene::kMaxParticles) +
                                " particles are allowed)");
  }
  dem.mutable_packing_file()->set_path(file.string());
  return dem;
}

// Its own part of the scene, or a clear refusal: the DEM never reads the fluid's.
const wire::DemConfig& dem_part(const wire::Init& init) {
  if (init.has_dem()) return init.dem();
  throw std::invalid_argument(
      std::string("dem_module: Init carries no DEM part (Init.dem, a DemConfig with the scene's "
                  "dem block)") +
      (init.has_fluid() ? "; it carries the fluid's part (Init.fluid), which is for fluid_module"
                        : "") +
      "; a coupler of protocol " + std::to_string(wire::kProtocolVersion) + " sends it");
}

}  // namespace

void DemService::init(const wire::Init& init, wire::Message& reply) {
  const wire::DemConfig& config = dem_part(init);
  scene::validate_received(config);
  setup_ = build_dem(with_allowed_packing_file(config, read_root_));
  if (setup_.system->particles().size() > scene::kMaxParticles) {
    setup_ = {};
    throw std::invalid_argument("the packing file holds more than " +
                                std::to_string(scene::kMaxParticles) + " particles");
  }
  position_at_exchange_ = setup_.system->particles().position;

  wire::InitReply* r = reply.envelope.mutable_init_reply();
  r->set_model("dem");
  r->set_particle_count(setup_.system->particles().size());
  if (config.coupled()) r->add_needs(std::string(wire::field::kForce));
  for (auto f : kProvided) r->add_provides(std::string(f));
  if (setup_.critical.dt_s > 0) {
    wire::StabilityLimit* l = r->add_limits();
    l->set_name("dem_springs");
    l->set_dt_max_s(setup_.critical.dt_s);
    l->set_detail(setup_.critical.detail);
    l->set_kind(wire::LIMIT_KIND_DEM_SPRINGS);
  }
  *r->mutable_solid() = solid_properties(config.dem());
  if (!setup_.specimen_report.empty()) r->add_notes(setup_.specimen_report);
  const std::string advice = thread_advice(setup_.system->particles().size(),
                                           static_cast<int>(config.dem().threads()));
  if (!advice.empty()) r->add_notes(advice);
}

void DemService::subscribe(const wire::Subscribe& subscribe, wire::Message& reply) {
  system();
  for (const std::string& f : subscribe.fields()) {
    if (std::find(kProvided.begin(), kProvided.end(), f) == kProvided.end() || f == "breaks") {
      throw std::invalid_argument("dem_module cannot provide the per-step field '" + f + "'");
    }
  }
  send_fields_.assign(subscribe.fields().begin(), subscribe.fields().end());
  // A membrane's dead load (biaxial test) is a supply of energy like a wall's push.
  setup_.guards.external_force_supplies_energy =
      subscribe.external_force_supplies_energy() || !setup_.system->membrane_load().particles.empty();
  reply.envelope.mutable_ack();
}

void DemService::after_reply() {
  if (setup_.system && setup_.system->in_split_step() &&
      !setup_.system->internal_forces_current()) {
    setup_.system->compute_internal_forces();
  }
}

void DemService::advance(const wire::Message& request, wire::Message& reply) {
  const wire::Advance& advance = request.envelope.advance();
  DemSystem& s = system();
  if (!stopped_by_.empty()) {
    throw std::runtime_error("dem_module: stopped by the " + stopped_by_ +
                             " guard; only frames can be asked for");
  }
  s.extrapolate_external_force(advance.extrapolate_fluid_force());
  s.correct_lag_passively(advance.lag_passivity());
  s.stiffen_external_force(advance.fluid_self_stiffness());
  if (advance.apply_forces_first()) {
    // The held ApplyForces of the last exchange (no output was due at its step). The guards run
    // on the completed step at the same cadence as inside a long Advance.
    hold_forces(request);
    if (s.step_count() >= guard_checked_step_ + kGuardEverySteps) {
      guard_checked_step_ = s.step_count();
      if (check_guards(s, setup_.guards, setup_.initial_energy_j, s.kinetic_energy()).tripped()) {
        return report(reply);
      }
    }
  }
  const double dt = advance.dt_s();
  if (advance.steps() > 0 && !(dt > 0.0)) throw std::invalid_argument("Advance with dt_s <= 0");
  const unsigned full_steps = advance.split_last() && advance.steps() > 0 ? advance.steps() - 1
                                                                            : advance.steps();
  bool tripped = false;
  for (unsigned k = 0; k < full_steps; ++k) {
    s.step(dt);
    // A long Advance is checked on the way (the report checks again at its end): a blow-up stops
    // within kGuardEverySteps steps, with the state that tripped the guard.
    if (k % kGuardEverySteps == kGuardEverySteps - 1 && k + 1 < full_steps &&
        check_guards(s, setup_.guards, setup_.initial_energy_j, s.kinetic_energy()).tripped()) {
      tripped = true;
      break;
    }
  }
  // A guard inside a split Advance ends it with the report that names the guard, not with
  // kinematics of fewer steps than asked (which the coupler took for a module's failure).
  if (tripped || !advance.split_last()) return report(reply);

  if (advance.steps() > 0) s.begin_step(dt);
  // Without overlap (Coupling.overlap) the forces at x^{n+N} come now; after_reply then has
  // nothing to do.
  if (advance.steps() > 0 && advance.forces_before_reply()) s.compute_internal_forces();
  split_dt_s_ = advance.steps() > 0 ? dt : 0.0;
  wire::Kinematics* k = reply.envelope.mutable_kinematics();
  k->set_time_s(s.time_s());
  k->set_step(s.step_count());
  if (setup_.tool.present) {
    const WallBody& tool = s.walls().bodies()[setup_.tool.body];
    (*k->mutable_scalars())["tool_tip_x_m"] = setup_.tool.tip_x0_m + tool.offset_x;
    (*k->mutable_scalars())["tool_tip_y_m"] = setup_.tool.tip_y_m + tool.offset_y;
  }
  for (const std::string& f : send_fields_) add_field(f, reply);
  if (std::find(send_fields_.begin(), send_fields_.end(), wire::field::kDisplacement) !=
      send_fields_.end()) {
    position_at_exchange_ = s.particles().position;
  }
}

void DemService::hold_forces(const wire::Message& request) {
  DemSystem& s = system();
  const auto force = request.array(wire::field::kForce, 2, s.particles().size());
  std::span<const double> stiffness;  // K_ii, where the run applies it between exchanges
  if (s.fluid_self_stiffness().on) {
    stiffness = request.array(wire::field::kSelfStiffness, 3, s.particles().size());
  }
  if (s.in_split_step()) {
    s.finish_step(split_dt_s_, force, stiffness);
  } else {
    s.set_external_force(force, stiffness);  // t = 0 exchange: a^0 includes the fluid force
  }
}

void DemService::apply_forces(const wire::Message& request, wire::Message& reply) {
  hold_forces(request);
  report(reply);
}

void DemService::report(wire::Message& reply) {
  const DemSystem& s = *setup_.system;
  s.phases().write(reply.envelope);
  wire::StepReport* r = reply.envelope.mutable_step_report();
  r->set_time_s(s.time_s());
  r->set_step(s.step_count());
  auto& out = *r->mutable_scalars();
  const double kinetic = s.kinetic_energy();
  out["kinetic_energy_j"] = kinetic;
  check_guards_into(kinetic, *r);
  guard_checked_step_ = s.step_count();
  if (!s.bonds().size() && s.contacts().size() == 0 && s.walls().empty()) return;

  const EnergyLedger& e = s.ledger();
  const double strain = s.strain_energy();
  out["strain_energy_j"] = strain;
  // The energy budget (DESIGN section 5): what the run was given (initial energy, work of the
  // walls, the tool and the external forces) against where it went. The imbalance is relative to
  // the energy throughput, so that work given and taken back (a fluid force) counts both ways.
  const double given =
      setup_.initial_energy_j + e.boundary_work_j + e.external_work_j + e.gravity_work_j;
  const double held = kinetic + strain + e.damping_j + e.friction_j + e.broken_bond_j +
                      e.viscous_damping_j + e.rolling_j + e.lag_correction_j;
  const double throughput =
      setup_.initial_energy_j + std::abs(e.boundary_work_j) + std::abs(e.external_work_j) +
      std::abs(e.gravity_work_j);
  out["energy_imbalance_j"] = given - held;
  out["energy_imbalance_rel"] = throughput > 0 ? std::abs(given - held) / throughput : 0.0;
  out["boundary_work_j"] = e.boundary_work_j;
  out["external_work_j"] = e.external_work_j;
  out["gravity_work_j"] = e.gravity_work_j;
  out["damping_j"] = e.damping_j;
  out["friction_j"] = e.friction_j;
  out["broken_bond_j"] = e.broken_bond_j;
  out["viscous_damping_j"] = e.viscous_damping_j;
  if (e.viscous_damping_j > 0) out["viscous_damping_bonds_j"] = e.viscous_damping_bonds_j;
  out["rolling_j"] = e.rolling_j;
  if (s.lag_passivity().on) out["lag_correction_j"] = e.lag_correction_j;
  out["bonds"] = static_cast<double>(s.bonds().size());
  // Since the run's start (kept over resumes): what a cut's flying fragments cost in list work.
  out["neighbour_rebuilds"] = static_cast<double>(s.neighbour_rebuilds());
  if (s.bonds().law().softening_ratio > 0) {
    out["bond_softening_j"] = e.bond_softening_j;
    std::size_t damaged = 0;
    for (std::size_t k = 0; k < s.bonds().size(); ++k) damaged += s.bonds().damage(k) > 0.0;
    out["bonds_damaged"] = static_cast<double>(damaged);
  }
  std::size_t tensile = 0;
  for (const BondBreak& b : s.breaks()) tensile += b.mode == BreakMode::tensile;
  out["breaks_tensile"] = static_cast<double>(tensile);
  out["breaks_shear"] = static_cast<double>(s.breaks().size() - tensile);
  if (s.bonds().size() > 0 || !s.breaks().empty()) {
    const ChipStats chips = chip_stats(s.particles(), s.bonds());
    out["chips"] = static_cast<double>(chips.chips);
    out["chip_area_mean_m2"] = chips.mean_area_m2;
  }
  if (setup_.rig.present) report_rig(out);
  for (std::size_t b = 0; b < s.walls().bodies().size(); ++b) {
    const WallBody& body = s.walls().bodies()[b];
    if (setup_.tool.present && b == setup_.tool.body) {
      out["tool_force_x_n_per_m"] = body.force_x;
      out["tool_force_y_n_per_m"] = body.force_y;
      const double tip_x = setup_.tool.tip_x0_m + body.offset_x;
      out["tool_travel_m"] = tip_x - setup_.tool.specimen_left_m;
      out["tool_tip_x_m"] = tip_x;
      out["tool_tip_y_m"] = setup_.tool.tip_y_m + body.offset_y;
      continue;
    }
    const std::string prefix = "wall_" + body.name + "_";
    out[prefix + "force_x_n_per_m"] = body.force_x;
    out[prefix + "force_y_n_per_m"] = body.force_y;
    out[prefix + "offset_x_m"] = body.offset_x;
    out[prefix + "offset_y_m"] = body.offset_y;
  }
}

void DemService::check_guards_into(double kinetic_energy_j, wire::StepReport& report) {
  const GuardFinding f = check_guards(*setup_.system, setup_.guards, setup_.initial_energy_j,
                                      kinetic_energy_j);
  if (!f.tripped()) return;
  stopped_by_ = f.guard;
  wire::GuardTrip* g = report.mutable_guard();
  g->set_guard(f.guard);
  g->set_message(f.message);
  g->set_time_s(setup_.system->time_s());
  g->set_particle(f.particle);
  g->set_x_m(f.x_m);
  g->set_y_m(f.y_m);
  g->set_value(f.value);
  g->set_limit(f.limit);
}

void DemService::report_rig(google::protobuf::Map<std::string, double>& out) {
  const DemSystem& s = *setup_.system;
  const LoadingRig& rig = setup_.rig;
  const WallBody& top = s.walls().bodies()[rig.top];
  const WallBody& bottom = s.walls().bodies()[rig.bottom];
  // The discs push the top platen up and the bottom one down: the mean of both is the load. With
  // clamped end layers the platens also hold those layers (their reactions).
  double force = 0.5 * (top.force_y - bottom.force_y);
  if (rig.clamped_ends) {
    force += 0.5 * (s.clamped_group(rig.top_layer_group).reaction_y_n_per_m -
                    s.clamped_group(rig.bottom_layer_group).reaction_y_n_per_m);
  }
  out["platen_force_n_per_m"] = force;
  out["axial_strain"] = (bottom.offset_y - top.offset_y) / rig.height0_m;
  if (rig.fracture) {
    // The pull (tension positive) and how far the pulling ends have moved apart.
    out["pulling_force_n_per_m"] = -force;
    out["elongation_m"] = top.offset_y - bottom.offset_y;
    out["ligament_m"] = rig.ligament_m;
  }
  if (rig.ucs) out["axial_stress_pa"] = force / rig.width0_m;  // per unit thickness: N/m / m = Pa
  if (rig.biaxial) {
    // sigma_3 over the loaded length: the mean of the walls' pressing forces, or the membrane's
    // line load sigma_c H (a dead load: it rises as the specimen shortens).
    const double length_m = rig.height0_m + top.offset_y - bottom.offset_y;
    const MembraneLoad& m = s.membrane_load();
    const double pressing = rig.side_walls ? 0.5 * (s.walls().bodies()[rig.right_wall].force_x -
                                                    s.walls().bodies()[rig.left_wall].force_x)
                                           : m.stress_pa * m.height_m;
    out["lateral_stress_pa"] = pressing / length_m;
  }
  // UCS: the specimen's lateral strain. Brazilian: the opening of the disc across its horizontal
  // diameter over D, which jumps when the disc splits (the split detector's input).
  const Particles& p = s.particles();
  const double width =
      mean_coordinate(p, rig.right_strip, 0) - mean_coordinate(p, rig.left_strip, 0);
  out["lateral_strain"] = (width - rig.strip_width0_m) / rig.strip_width0_m;
  if (rig.gauge_length0_m == 0.0) return;
  const double gauge =
      mean_coordinate(p, rig.upper_gauge, 1) - mean_coordinate(p, rig.lower_gauge, 1);
  out["axial_strain_gauge"] = (rig.gauge_length0_m - gauge) / rig.gauge_length0_m;  // compression +
}

void DemService::frame(const wire::FrameRequest& request, wire::Message& reply) {
  system();
  reply.envelope.mutable_frame()->set_time_s(setup_.system->time_s());
  for (const std::string& f : request.fields()) add_field(f, reply);
}

void DemService::add_field(std::string_view field, wire::Message& reply) {
  const Particles& p = setup_.system->particles();
  if (field == wire::field::kPosition) return reply.add_array(field, p.position, 2);
  if (field == wire::field::kVelocity || field == wire::field::kVelocityHalf) {
    return reply.add_array(field, p.velocity, 2);
  }
  if (field == wire::field::kRadius) return reply.add_array(field, p.radius, 1);
  if (field == wire::field::kForce) return reply.add_array(field, p.force, 2);
  if (field == wire::field::kExternalForce) return reply.add_array(field, p.external_force, 2);
  if (field == "angular_velocity") return reply.add_array(field, p.angular_velocity, 1);
  if (field == wire::field::kDisplacement) {
    scratch_.resize(p.position.size());
    for (std::size_t k = 0; k < scratch_.size(); ++k) {
      scratch_[k] = p.position[k] - position_at_exchange_[k];
    }
    return reply.add_array(field, scratch_, 2);
  }
  if (field == wire::field::kWallSegments) {
    // Not per particle: the walls' and the tool's segments where they are now.
    const WallSet& walls = setup_.system->walls();
    scratch_.clear();
    for (const Segment& seg : walls.segments()) {
      const WallBody& b = walls.bodies()[seg.body];
      scratch_.insert(scratch_.end(), {seg.ax + b.offset_x, seg.ay + b.offset_y,
                                       seg.bx + b.offset_x, seg.by + b.offset_y});
    }
    return reply.add_array(field, scratch_, 4);
  }
  if (field == "damage") {
    // Paper figures 11-12: D = 1 - bonds / initial bonds (0 for a disc that never had a bond).
    setup_.system->bonds().count_per_particle(p.size(), bond_count_);
    scratch_.resize(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double initial = setup_.initial_bonds[i];
      scratch_[i] = initial > 0 ? 1.0 - bond_count_[i] / initial : 0.0;
    }
    return reply.add_array(field, scratch_, 1);
  }
  if (field == "breaks") {
    const auto& all = setup_.system->breaks();
    std::vector<double> time, position, mode;
    for (std::size_t k = breaks_sent_; k < all.size(); ++k) {
      time.push_back(all[k].time_s);
      position.insert(position.end(), {all[k].x_m, all[k].y_m});
      mode.push_back(static_cast<double>(all[k].mode));
    }
    breaks_sent_ = all.size();
    reply.add_array("break_time_s", time, 1);
    reply.add_array("break_position", position, 2);
    reply.add_array("break_mode", mode, 1);
    return;
  }
  throw std::invalid_argument("dem_module cannot provide the field '" + std::string(field) + "'");
}

void DemService::save_state(wire::Message& reply) {
  const DemSystem& s = system();
  if (!stopped_by_.empty()) {
    throw std::runtime_error("dem_module: stopped by the " + stopped_by_ +
                             " guard; its state is not worth a checkpoint");
  }
  if (s.in_split_step()) {
    throw std::runtime_error("dem_module: SaveState inside a split step (ApplyForces first)");
  }
  state::StateArchive archive;
  s.save_state(archive);
  // The service's own part: what "displacement" is measured from, the breaks already handed
  // out in frames, and the step the guards last ran on.
  archive.put("position_at_exchange_m", position_at_exchange_, 2);
  archive.put_scalar("breaks_sent", static_cast<double>(breaks_sent_));
  archive.put_scalar("guard_checked_step", static_cast<double>(guard_checked_step_));
  wire::State* body = reply.envelope.mutable_state();
  body->set_module(name() + " " + version());
  wire::put_state(archive, *body, reply);
}

void DemService::load_state(const wire::Message& request, wire::Message& reply) {
  DemSystem& s = system();
  const state::StateArchive archive =
      wire::take_state(request.envelope.load_state().state(), request);
  s.load_state(archive);
  archive.get("position_at_exchange_m", position_at_exchange_, s.particles().position.size());
  breaks_sent_ = archive.scalar_as<std::size_t>("breaks_sent");
  if (breaks_sent_ > s.breaks().size()) {
    throw state::StateError("state member \"breaks_sent\" exceeds the breaks saved");
  }
  guard_checked_step_ = archive.scalar_as<std::uint64_t>("guard_checked_step");
  split_dt_s_ = 0.0;
  reply.envelope.mutable_ack();
}

namespace {
int serve_inproc(zmq::context_t& context, const std::string& endpoint) {
  DemService service;
  return wire::serve(context, endpoint, service);
}
const bool registered = wire::register_inproc_module(wire::MODULE_KIND_DEM, &serve_inproc);
}  // namespace

}  // namespace rockcut::dem
