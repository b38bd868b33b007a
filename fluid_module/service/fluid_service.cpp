#include "service/fluid_service.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "models/registry.hpp"
#include "sp/format.hpp"
#include "scene/particle_budget.hpp"
#include "scene/validation.hpp"
#include "wire/inproc_registry.hpp"
#include "wire/protocol.hpp"
#include "wire/state_message.hpp"

namespace rockcut::fluid {

namespace {
bool contains(const std::vector<std::string>& v, std::string_view s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

// Its own part of the scene, or a clear refusal: the fluid never reads the DEM's.
const wire::FluidConfig& fluid_part(const wire::Init& init) {
  if (init.has_fluid()) return init.fluid();
  throw std::invalid_argument(
      std::string("fluid_module: Init carries no fluid part (Init.fluid, a FluidConfig with the "
                  "scene's fluid block, water_depth_m and the DEM's solid properties)") +
      (init.has_dem() ? "; it carries the DEM's part (Init.dem), which is for dem_module" : "") +
      "; a coupler of protocol " + std::to_string(wire::kProtocolVersion) + " sends it");
}

wire::LimitKind wire_kind(LimitKind kind) {
  switch (kind) {
    case LimitKind::diffusion: return wire::LIMIT_KIND_FLUID_DIFFUSION;
    case LimitKind::pore_fluid_stiffness: return wire::LIMIT_KIND_PORE_FLUID_STIFFNESS;
    case LimitKind::pore_fluid_stiffness_extrapolated:
      return wire::LIMIT_KIND_PORE_FLUID_STIFFNESS_EXTRAPOLATED;
    case LimitKind::other: break;
  }
  return wire::LIMIT_KIND_UNSPECIFIED;
}
}  // namespace

std::string FluidService::version() const { return ROCKCUT_VERSION; }

std::vector<std::string> FluidService::models() const { return model_names(); }

FluidModel& FluidService::model() {
  if (!model_) throw std::logic_error("fluid_module: request before Init");
  return *model_;
}

void FluidService::handle(const wire::Message& request, wire::Message& reply) {
  const wire::Envelope& e = request.envelope;
  switch (e.body_case()) {
    case wire::Envelope::kInit: return init(request, reply);
    case wire::Envelope::kFluidStep: return step(request, reply);
    case wire::Envelope::kFrameRequest: return frame(e.frame_request(), reply);
    case wire::Envelope::kSaveState: return save_state(reply);
    case wire::Envelope::kLoadState: return load_state(request, reply);
    default:
      throw std::invalid_argument("fluid_module: unexpected request (envelope body " +
                                  std::to_string(e.body_case()) + ")");
  }
}

void FluidService::init(const wire::Message& request, wire::Message& reply) {
  // Threads of this module's OpenMP loops (the calling thread's setting: in an inproc run the
  // DEM thread keeps its own).
  // Its part is checked with the coupler's rules first: threads within (max), finite numbers.
  const wire::FluidConfig& config = fluid_part(request.envelope.init());
  scene::validate_received(config);
  omp_set_num_threads(static_cast<int>(std::max(1u, config.fluid().threads())));
  model_ = make_model(config);
  needs_ = model_->needs();
  StaticData data;
  const std::vector<std::string> needs_static = model_->needs_static();
  if (contains(needs_static, wire::field::kRadius)) {
    data.radius = request.array(wire::field::kRadius, 1);
    particle_count_ = data.radius.size();
  }
  if (contains(needs_static, wire::field::kPosition)) {
    data.position = contains(needs_static, wire::field::kRadius)
                        ? request.array(wire::field::kPosition, 2, particle_count_)
                        : request.array(wire::field::kPosition, 2);
    particle_count_ = data.position.size() / 2;
  }
  if (particle_count_ > scene::kMaxParticles) {
    throw std::invalid_argument("fluid_module: Init sends " + std::to_string(particle_count_) +
                                " particles; at most " + std::to_string(scene::kMaxParticles) +
                                " are allowed");
  }
  derive_displacement_ =
    contains(needs_, wire::field::kDisplacement) && contains(needs_, wire::field::kPosition);
  if (derive_displacement_) {
    // Init's positions are the DEM's at the start, which its displacement is taken from too.
    const std::span<const double> x0 = request.array(wire::field::kPosition, 2);
    previous_position_.assign(x0.begin(), x0.end());
    displacement_.assign(x0.size(), 0.0);
  }
  model_->initialise(data);
  force_.assign(2 * particle_count_, 0.0);

  wire::InitReply* r = reply.envelope.mutable_init_reply();
  r->set_model(model_->name());
  r->set_particle_count(particle_count_);
  r->set_supplies_energy(model_->supplies_energy());
  for (const auto& f : needs_) {
    if (!(derive_displacement_ && f == wire::field::kDisplacement)) r->add_needs(f);
  }
  r->add_provides(std::string(wire::field::kForce));
  for (const auto& f : model_->provides()) r->add_provides(f);
  for (const StabilityLimit& l : model_->limits()) {
    wire::StabilityLimit* w = r->add_limits();
    w->set_name(l.name);
    w->set_dt_max_s(l.dt_max_s);
    w->set_detail(l.detail);
    w->set_lag_only(l.lag_only);
    w->set_remedy(l.remedy);
    w->set_kind(wire_kind(l.kind));
  }
}

void FluidService::step(const wire::Message& request, wire::Message& reply) {
  FluidModel& m = model();
  const wire::FluidStep& s = request.envelope.fluid_step();
  Kinematics k;
  // Every per-particle array must have the particles of Init: the model indexes them by particle.
  const std::size_t n = particle_count_;
  if (contains(needs_, wire::field::kPosition)) {
    k.position = request.array(wire::field::kPosition, 2, n);
  }
  if (contains(needs_, wire::field::kVelocityHalf)) {
    k.velocity_half = request.array(wire::field::kVelocityHalf, 2, n);
  }
  if (derive_displacement_) {
    if (k.position.size() != previous_position_.size()) {
      throw std::invalid_argument("fluid_module: FluidStep has " +
                                  std::to_string(k.position.size() / 2) + " positions, Init had " +
                                  std::to_string(previous_position_.size() / 2));
    }
    // One pass on the model's threads (a per-element difference: the same bits at any count).
    const double* x = k.position.data();
    double* x0 = previous_position_.data();
    double* d = displacement_.data();
    const auto count = static_cast<std::ptrdiff_t>(displacement_.size());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < count; ++i) {
      d[i] = x[i] - x0[i];
      x0[i] = x[i];
    }
    k.displacement = displacement_;
  } else if (contains(needs_, wire::field::kDisplacement)) {
    k.displacement = request.array(wire::field::kDisplacement, 2, n);
  }
  if (contains(needs_, wire::field::kWallSegments)) {
    k.wall_segments = request.array(wire::field::kWallSegments, 4);
  }
  if (!std::isfinite(s.dt_s()) || s.dt_s() < 0.0 || !std::isfinite(s.time_s())) {
    throw std::invalid_argument("fluid_module: FluidStep with dt_s or time_s not finite, or dt_s < 0");
  }
  m.step(s.dt_s(), s.time_s(), k, force_);
  wire::FluidResult* result = reply.envelope.mutable_fluid_result();
  guard_not_finite(s.time_s(), k.position, *result);
  reply.add_array(wire::field::kForce, force_, 2);
  if (s.self_stiffness()) {  // the grain's own stiffness, for the DEM between exchanges
    if (!m.self_stiffness(self_stiffness_)) {
      throw std::invalid_argument("fluid model " + m.name() +
                                  " has no self stiffness to give (coupling.fluid_stiffness "
                                  "\"self\" needs one; use \"none\")");
    }
    reply.add_array(wire::field::kSelfStiffness, self_stiffness_, 3);
  }
  if (!s.report()) return;  // nothing records this exchange
  if (const wire::PhaseClock* phases = m.phases()) phases->write(reply.envelope);
  m.scalars(scalars_);
  for (const auto& [name, value] : scalars_) (*result->mutable_scalars())[name] = value;
  // Pressure nodes: averaged over the particle centres of this step.
  for (const wire::Probe& p : s.probes()) {
    double mean = 0.0;
    std::size_t count = 0;
    if (!m.probe(k.position, {p.x_min_m(), p.y_min_m(), p.x_max_m(), p.y_max_m()}, mean, count)) {
      throw std::invalid_argument("fluid model " + m.name() + " has no pressure to probe");
    }
    (*result->mutable_scalars())["probe_" + p.name() + "_pa"] = mean;
    (*result->mutable_scalars())["probe_" + p.name() + "_particles"] = static_cast<double>(count);
  }
}

void FluidService::guard_not_finite(double time_s, std::span<const double> position,
                                    wire::FluidResult& result) const {
  // The runtime NaN guard (DESIGN section 5) for any model: the forces it hands the DEM. Any
  // non-finite value is first looked for on the model's threads (0 * inf and 0 * NaN are NaN);
  // the rare search for the first one is serial.
  const double* f = force_.data();
  const auto count = static_cast<std::ptrdiff_t>(force_.size());
  double zero_unless_bad = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : zero_unless_bad)
  for (std::ptrdiff_t k = 0; k < count; ++k) zero_unless_bad += 0.0 * f[k];
  if (zero_unless_bad == 0.0) return;
  const auto bad = std::find_if(force_.begin(), force_.end(), [](double v) { return !std::isfinite(v); });
  if (bad == force_.end()) return;
  const std::int64_t i = (bad - force_.begin()) / 2;
  wire::GuardTrip* g = result.mutable_guard();
  g->set_guard("nan");
  g->set_time_s(time_s);
  g->set_particle(i);
  std::string where;
  if (position.size() >= static_cast<std::size_t>(2 * i + 2)) {
    g->set_x_m(position[2 * i]);
    g->set_y_m(position[2 * i + 1]);
    where = " at (" + sp::fmt(position[2 * i]) + ", " + sp::fmt(position[2 * i + 1]) + ") m";
  }
  g->set_message("the " + model_->name() + " fluid force on particle " + std::to_string(i) + where +
                 " is not finite at t = " + sp::fmt(time_s) + " s");
}

void FluidService::frame(const wire::FrameRequest& request, wire::Message& reply) {
  FluidModel& m = model();
  reply.envelope.mutable_frame();
  for (const std::string& field : request.fields()) {
    if (field == wire::field::kForce) {
      reply.add_array(field, force_, 2);
      continue;
    }
    m.output(field, output_);
    reply.add_array(field, output_, output_.size() == 2 * particle_count_ ? 2 : 1);
  }
}

void FluidService::save_state(wire::Message& reply) {
  const FluidModel& m = model();
  state::StateArchive archive;
  m.save_state(archive);
  // The service's own part: the last forces handed out (a frame may ask for them) and the
  // positions the next displacement is measured from.
  archive.put("service_force_n_per_m", force_, 2);
  archive.put("service_previous_position_m", previous_position_, 2);
  wire::State* body = reply.envelope.mutable_state();
  body->set_module(name() + " " + version());
  archive.put_text("model", m.name());
  wire::put_state(archive, *body, reply);
}

void FluidService::load_state(const wire::Message& request, wire::Message& reply) {
  FluidModel& m = model();
  const state::StateArchive archive =
      wire::take_state(request.envelope.load_state().state(), request);
  if (archive.text("model") != m.name()) {
    throw state::StateError("the state is of fluid model \"" + archive.text("model") +
                            "\", this run's is \"" + m.name() + "\"");
  }
  m.load_state(archive);
  archive.get("service_force_n_per_m", force_, force_.size());
  archive.get("service_previous_position_m", previous_position_, previous_position_.size());
  reply.envelope.mutable_ack();
}

namespace {
int serve_inproc(zmq::context_t& context, const std::string& endpoint) {
  FluidService service;
  return wire::serve(context, endpoint, service);
}
const bool registered = wire::register_inproc_module(wire::MODULE_KIND_FLUID, &serve_inproc);
}  // namespace

}  // namespace rockcut::fluid
