#include "schemes/half_step_exchange.hpp"

#include "run/reply_checks.hpp"
#include "wire/protocol.hpp"

namespace rockcut::coupler {

HalfStepExchange::HalfStepExchange(const TimePlan& plan, RunModules& modules,
                                   const RunObservers& observers)
    : CouplingScheme(plan), modules_(modules), dem_(modules.dem()), fluid_(*modules.fluid()),
      observers_(observers) {}

void HalfStepExchange::exchange(RunClock& clock, unsigned steps, bool initial,
                                const ExchangeSchedule* schedule) {
  // 1. DEM: (complete the last step with the held fluid force,) N-1 full steps, then half kick and
  //    drift; answers x^{n+N}, v^{n+N-1/2}.
  dem_.request.clear();
  wire::Advance* advance = dem_.request.envelope.mutable_advance();
  advance->set_steps(steps);
  advance->set_dt_s(plan_.dt_s);
  advance->set_split_last(true);
  advance->set_forces_before_reply(plan_.forces_before_reply);
  advance->set_extrapolate_fluid_force(plan_.extrapolate_fluid_force);
  advance->set_lag_passivity(plan_.lag_passivity);
  advance->set_fluid_self_stiffness(plan_.fluid_self_stiffness);
  if (forces_held_) {
    advance->set_apply_forces_first(true);
    dem_.request.take_arrays(fluid_.reply);
    forces_held_ = false;
  }
  dem_.link->set_timeout(modules_.allowance(steps));
  dem_.link->request(dem_.request, dem_.reply);
  if (dem_.reply.envelope.has_step_report()) {
    const wire::StepReport& r = dem_.reply.envelope.step_report();
    // A guard tripped on the completed step, or on the way through the N steps: the report's
    // scalars replace the last exchange's (the row and frame of the stop are written from them).
    check_progress(dem_.label(), r.step(), r.time_s(), clock.step, clock.time_s, steps, true);
    clock.scalars.clear();
    clock.take_step_report(r, dem_.label());
  }
  if (!dem_.reply.envelope.has_kinematics()) {
    throw wire::ModuleFailure(dem_.label(), "answered Advance without Kinematics");
  }
  const wire::Kinematics& kinematics = dem_.reply.envelope.kinematics();
  const double t = kinematics.time_s();
  const std::uint64_t kinematics_step = kinematics.step();  // dem_.reply is reused below
  check_progress(dem_.label(), kinematics_step, t, clock.step, clock.time_s, steps, false);
  dem_.busy.read(dem_.reply.envelope);

  // 2. Fluid: advance the pressure by N dt (nothing at t = 0) and return the forces. The DEM
  //    computes its contact forces meanwhile. Arrays are forwarded, not copied.
  fluid_.request.clear();
  wire::FluidStep* fs = fluid_.request.envelope.mutable_fluid_step();
  fs->set_dt_s(initial ? 0.0 : steps * plan_.dt_s);
  fs->set_time_s(t);
  // The fluid's scalars (and the observers' probes) only where this exchange is recorded.
  const bool record = initial || schedule->completes_step_at(kinematics_step, t);
  fs->set_report(record);
  fs->set_self_stiffness(plan_.fluid_self_stiffness);
  if (record) observers_.each([&](RunObserver& o) { o.prepare_fluid_step(kinematics, *fs); });
  clock.bytes_exchanged += dem_.reply.payload_bytes();
  clock.bytes_in_shared_memory += dem_.reply.shared_payload_bytes();
  fluid_.request.take_arrays(dem_.reply);
  fluid_.link->request(fluid_.request, fluid_.reply);
  if (!fluid_.reply.envelope.has_fluid_result()) {
    throw wire::ModuleFailure(fluid_.label(), "answered FluidStep without FluidResult");
  }
  checked_array(fluid_.label(), fluid_.reply, std::string(wire::field::kForce), 2,
                modules_.particle_count());
  fluid_.busy.read(fluid_.reply.envelope);
  if (fluid_.reply.envelope.fluid_result().has_guard()) {
    throw GuardStop{fluid_.label(), fluid_.reply.envelope.fluid_result().guard()};
  }
  clock.bytes_exchanged += fluid_.reply.payload_bytes();
  clock.bytes_in_shared_memory += fluid_.reply.shared_payload_bytes();
  ++clock.exchanges;

  // 3. DEM: total force at x^{n+N}, second half kick. When nothing is recorded at this step, the
  //    force rides on the next Advance instead.
  if (!record) {
    forces_held_ = true;
    clock.step = kinematics_step;
    clock.time_s = t;
    return;
  }
  dem_.request.clear();
  dem_.request.envelope.mutable_apply_forces();
  dem_.request.take_arrays(fluid_.reply);
  dem_.link->request(dem_.request, dem_.reply);
  if (!dem_.reply.envelope.has_step_report()) {
    throw wire::ModuleFailure(dem_.label(), "answered ApplyForces without StepReport");
  }
  check_progress(dem_.label(), dem_.reply.envelope.step_report().step(),
                 dem_.reply.envelope.step_report().time_s(), kinematics_step, t, 0, false);
  dem_.busy.read(dem_.reply.envelope);
  clock.scalars.clear();
  check_scalar_names(fluid_.label(), fluid_.reply.envelope.fluid_result().scalars());
  for (const auto& [name, value] : fluid_.reply.envelope.fluid_result().scalars()) {
    clock.scalars.emplace_back("fluid_" + name, value);
  }
  clock.take_step_report(dem_.reply.envelope.step_report(), dem_.label());
}

}  // namespace rockcut::coupler
