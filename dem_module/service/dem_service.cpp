#include "service/dem_service.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/lattice.hpp"
#include "wire/inproc_registry.hpp"
#include "wire/protocol.hpp"

namespace rockcut::dem {

namespace {

// Fields this module can put on the wire.
const std::vector<std::string_view> kProvided = {
    wire::field::kPosition, wire::field::kVelocity, wire::field::kVelocityHalf,
    wire::field::kDisplacement, wire::field::kRadius, wire::field::kForce,
    wire::field::kExternalForce};

Particles particles_from_scene(const rockcut::Dem& dem) {
  switch (dem.particles_case()) {
    case rockcut::Dem::kLattice: {
      const rockcut::Lattice& l = dem.lattice();
      LatticeSpec spec;
      spec.nx = l.nx();
      spec.ny = l.ny();
      spec.spacing_m = l.spacing_m();
      spec.radius_m = l.radius_m();
      spec.origin_x_m = l.origin_m().x();
      spec.origin_y_m = l.origin_m().y();
      spec.density_kg_m3 = dem.density_kg_m3();
      return make_lattice(spec);
    }
    case rockcut::Dem::PARTICLES_NOT_SET:
      break;
  }
  throw std::invalid_argument("dem: the scene gives no particles (set dem.lattice)");
}

}  // namespace

std::string DemService::version() const { return ROCKCUT_VERSION; }

DemSystem& DemService::system() {
  if (!system_) throw std::logic_error("dem_module: request before Init");
  return *system_;
}

void DemService::handle(const wire::Message& request, wire::Message& reply) {
  const wire::Envelope& e = request.envelope;
  switch (e.body_case()) {
    case wire::Envelope::kInit: return init(e.init(), reply);
    case wire::Envelope::kAdvance: return advance(e.advance(), reply);
    case wire::Envelope::kApplyForces: return apply_forces(request, reply);
    case wire::Envelope::kSubscribe: return subscribe(e.subscribe(), reply);
    case wire::Envelope::kFrameRequest: return frame(e.frame_request(), reply);
    default:
      throw std::invalid_argument("dem_module: unexpected request (envelope body " +
                                  std::to_string(e.body_case()) + ")");
  }
}

void DemService::init(const wire::Init& init, wire::Message& reply) {
  const rockcut::Dem& dem = init.scene().dem();
  Particles particles = particles_from_scene(dem);
  const double vx = dem.initial_velocity_m_s().x(), vy = dem.initial_velocity_m_s().y();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    particles.velocity[2 * i] = vx;
    particles.velocity[2 * i + 1] = vy;
  }
  DemSettings settings;
  settings.gravity_x_m_s2 = dem.gravity_m_s2().x();
  settings.gravity_y_m_s2 = dem.gravity_m_s2().y();
  if (dem.has_prescribed_motion()) {
    const rockcut::PrescribedMotion& m = dem.prescribed_motion();
    PrescribedMotion motion;
    motion.strain_rate_xx_per_s = m.strain_rate_xx_per_s();
    motion.strain_rate_yy_per_s = m.strain_rate_yy_per_s();
    motion.origin_x_m = m.origin_m().x();
    motion.origin_y_m = m.origin_m().y();
    motion.start_time_s = m.start_time_s();
    if (m.has_end_time_s()) motion.end_time_s = m.end_time_s();
    settings.prescribed_motion = motion;
  }
  system_ = std::make_unique<DemSystem>(std::move(particles), settings);

  position_at_exchange_ = system_->particles().position;

  wire::InitReply* r = reply.envelope.mutable_init_reply();
  r->set_model("dem");
  r->set_particle_count(system_->particles().size());
  if (init.scene().has_fluid()) r->add_needs(std::string(wire::field::kForce));
  for (auto f : kProvided) r->add_provides(std::string(f));
  // Free discs without contacts have no stability limit of their own; contact and bond springs
  // (DESIGN section 5) add theirs here.
}

void DemService::subscribe(const wire::Subscribe& subscribe, wire::Message& reply) {
  system();
  for (const std::string& f : subscribe.fields()) {
    if (std::find(kProvided.begin(), kProvided.end(), f) == kProvided.end()) {
      throw std::invalid_argument("dem_module cannot provide the field '" + f + "'");
    }
  }
  send_fields_.assign(subscribe.fields().begin(), subscribe.fields().end());
  reply.envelope.mutable_ack();
}

void DemService::after_reply() {
  if (system_ && system_->in_split_step() && !system_->internal_forces_current()) {
    system_->compute_internal_forces();
  }
}

void DemService::advance(const wire::Advance& advance, wire::Message& reply) {
  DemSystem& s = system();
  const double dt = advance.dt_s();
  if (advance.steps() > 0 && !(dt > 0.0)) throw std::invalid_argument("Advance with dt_s <= 0");
  const unsigned full_steps = advance.split_last() && advance.steps() > 0 ? advance.steps() - 1
                                                                            : advance.steps();
  for (unsigned k = 0; k < full_steps; ++k) s.step(dt);
  if (!advance.split_last()) return report(reply);

  if (advance.steps() > 0) s.begin_step(dt);
  split_dt_s_ = advance.steps() > 0 ? dt : 0.0;
  wire::Kinematics* k = reply.envelope.mutable_kinematics();
  k->set_time_s(s.time_s());
  k->set_step(s.step_count());
  for (const std::string& f : send_fields_) add_field(f, reply);
  if (std::find(send_fields_.begin(), send_fields_.end(), wire::field::kDisplacement) !=
      send_fields_.end()) {
    position_at_exchange_ = s.particles().position;
  }
}

void DemService::apply_forces(const wire::Message& request, wire::Message& reply) {
  DemSystem& s = system();
  const auto force = request.array(wire::field::kForce, 2);
  if (s.in_split_step()) {
    s.finish_step(split_dt_s_, force);
  } else {
    s.set_external_force(force);  // t = 0 exchange: a^0 includes the fluid force
  }
  report(reply);
}

void DemService::report(wire::Message& reply) const {
  wire::StepReport* r = reply.envelope.mutable_step_report();
  r->set_time_s(system_->time_s());
  r->set_step(system_->step_count());
  (*r->mutable_scalars())["kinetic_energy_j"] = system_->kinetic_energy();
}

void DemService::frame(const wire::FrameRequest& request, wire::Message& reply) {
  system();
  reply.envelope.mutable_frame()->set_time_s(system_->time_s());
  for (const std::string& f : request.fields()) add_field(f, reply);
}

void DemService::add_field(std::string_view field, wire::Message& reply) {
  const Particles& p = system_->particles();
  if (field == wire::field::kPosition) return reply.add_array(field, p.position, 2);
  if (field == wire::field::kVelocity || field == wire::field::kVelocityHalf) {
    return reply.add_array(field, p.velocity, 2);
  }
  if (field == wire::field::kRadius) return reply.add_array(field, p.radius, 1);
  if (field == wire::field::kForce) return reply.add_array(field, p.force, 2);
  if (field == wire::field::kExternalForce) return reply.add_array(field, p.external_force, 2);
  if (field == wire::field::kDisplacement) {
    scratch_.resize(p.position.size());
    for (std::size_t k = 0; k < scratch_.size(); ++k) {
      scratch_[k] = p.position[k] - position_at_exchange_[k];
    }
    return reply.add_array(field, scratch_, 2);
  }
  throw std::invalid_argument("dem_module cannot provide the field '" + std::string(field) + "'");
}

namespace {
int serve_inproc(zmq::context_t& context, const std::string& endpoint) {
  DemService service;
  return wire::serve(context, endpoint, service);
}
const bool registered = wire::register_inproc_module(wire::MODULE_KIND_DEM, &serve_inproc);
}  // namespace

}  // namespace rockcut::dem
