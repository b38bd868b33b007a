#include "core/guards.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rockcut::dem {

namespace {

std::string format(const char* fmt, auto... args) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, fmt, args...);
  return buffer;
}

GuardFinding at_particle(const Particles& p, std::int64_t i, std::string guard, double value,
                         double limit) {
  GuardFinding f;
  f.guard = std::move(guard);
  f.particle = i;
  if (i >= 0) {
    f.x_m = p.position[2 * i];
    f.y_m = p.position[2 * i + 1];
  }
  f.value = value;
  f.limit = limit;
  return f;
}

// The first particle with a non-finite position, velocity, force or torque (-1: none).
std::int64_t first_not_finite(const Particles& p, const char*& what) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto bad = [&](const std::vector<double>& a, std::size_t per) {
      for (std::size_t c = 0; c < per; ++c) {
        if (!std::isfinite(a[per * i + c])) return true;
      }
      return false;
    };
    if (bad(p.position, 2)) what = "position";
    else if (bad(p.velocity, 2)) what = "velocity";
    else if (bad(p.angular_velocity, 1)) what = "angular velocity";
    else if (bad(p.external_force, 2)) what = "external (fluid) force";
    else if (bad(p.force, 2) || bad(p.torque, 1)) what = "force";
    else continue;
    return static_cast<std::int64_t>(i);
  }
  return -1;
}

}  // namespace

GuardLimits make_guard_limits(const Particles& p, double critical_time_s, double max_overlap_ratio,
                              double kinetic_energy_factor) {
  GuardLimits g;
  g.max_overlap_ratio = max_overlap_ratio;
  g.kinetic_energy_factor = kinetic_energy_factor;
  g.critical_time_s = critical_time_s;
  double mass = 0.0;
  g.r_min_m = p.size() ? p.radius[0] : 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    mass += 1.0 / p.inv_mass[i];
    g.r_min_m = std::min(g.r_min_m, p.radius[i]);
  }
  g.speed_limit_m_s = critical_time_s > 0 && max_overlap_ratio > 0
                          ? max_overlap_ratio * g.r_min_m / critical_time_s
                          : 0.0;
  const double floor_speed = g.speed_limit_m_s > 0 ? 1e-3 * g.speed_limit_m_s : 1e-3;
  g.kinetic_energy_floor_j = 0.5 * mass * floor_speed * floor_speed;
  return g;
}

OverlapExtreme largest_overlap(const DemSystem& system) {
  const Particles& p = system.particles();
  OverlapExtreme out;
  const auto pair = [&](std::uint32_t i, std::uint32_t j) {
    const double dx = p.position[2 * j] - p.position[2 * i];
    const double dy = p.position[2 * j + 1] - p.position[2 * i + 1];
    const double overlap = p.radius[i] + p.radius[j] - std::sqrt(dx * dx + dy * dy);
    const double ratio = overlap / std::min(p.radius[i], p.radius[j]);
    if (ratio > out.ratio) {
      out.ratio = ratio;
      out.particle = p.radius[i] <= p.radius[j] ? i : j;
    }
  };
  const BondSet& bonds = system.bonds();
  for (std::size_t k = 0; k < bonds.size(); ++k) pair(bonds.first(k), bonds.second(k));
  const ContactList& contacts = system.contacts();
  for (std::size_t k = 0; k < contacts.size(); ++k) pair(contacts.first(k), contacts.second(k));
  std::int64_t wall_particle = -1;
  const double wall = system.walls().largest_overlap_ratio(p, wall_particle);
  if (wall > out.ratio) out = {wall, wall_particle};
  return out;
}

double energy_supplied_j(const DemSystem& system, double initial_energy_j,
                         bool external_force_supplies_energy) {
  const EnergyLedger& e = system.ledger();
  return initial_energy_j + std::max(0.0, e.boundary_work_j) + std::max(0.0, e.gravity_work_j) +
         (external_force_supplies_energy ? std::max(0.0, e.external_work_j) : 0.0);
}

GuardFinding check_guards(const DemSystem& system, const GuardLimits& limits,
                          double initial_energy_j, double kinetic_energy_j) {
  if (!limits.enabled) return {};
  const Particles& p = system.particles();
  const double t = system.time_s();

  const char* what = "";
  std::int64_t i = first_not_finite(p, what);
  if (i < 0 && !std::isfinite(kinetic_energy_j)) {  // finite speeds whose squares overflow
    what = "kinetic energy (its speed squared overflows)";
    double v_max = -1.0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double v = std::abs(p.velocity[2 * k]) + std::abs(p.velocity[2 * k + 1]);
      if (v > v_max) v_max = v, i = static_cast<std::int64_t>(k);
    }
  }
  if (i >= 0) {
    GuardFinding f = at_particle(p, i, "nan", NAN, 0.0);
    f.message = format("%s of particle %lld is not finite at t = %.6g s (position %.6g, %.6g m)",
                       what, static_cast<long long>(i), t, f.x_m, f.y_m);
    return f;
  }

  if (limits.kinetic_energy_factor > 0) {
    const double supplied =
        energy_supplied_j(system, initial_energy_j, limits.external_force_supplies_energy);
    const double allowed = limits.kinetic_energy_factor * supplied + limits.kinetic_energy_floor_j;
    // The fluid is no energy source: it stores what the grains do on it and dissipates it by
    // flow, so its net work on the grains cannot exceed what the run was given either. A lagged
    // coupling that pumps energy shows here first (its work is damped out of sight).
    const double fluid_work =
        limits.external_force_supplies_energy ? 0.0 : system.ledger().external_work_j;
    if (kinetic_energy_j > allowed || fluid_work > allowed) {
      std::int64_t fastest = 0;
      double v2_max = -1.0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double v2 = p.velocity[2 * i] * p.velocity[2 * i] +
                          p.velocity[2 * i + 1] * p.velocity[2 * i + 1];
        if (v2 > v2_max) v2_max = v2, fastest = static_cast<std::int64_t>(i);
      }
      const bool by_fluid = !(kinetic_energy_j > allowed);
      const double value = by_fluid ? fluid_work : kinetic_energy_j;
      GuardFinding f = at_particle(p, fastest, "kinetic_energy", value, allowed);
      f.message = format(
          "runaway kinetic energy at t = %.6g s: %s %.4g J/m, more than %.3g times the %.4g J/m "
          "the run was given (energy is being created: the time step or the coupling interval is "
          "too large for this scene, or it needs damping); fastest particle %lld at (%.6g, %.6g) m "
          "moving at %.4g m/s",
          t, by_fluid ? "the external (fluid) force has put in" : "the kinetic energy is", value,
          limits.kinetic_energy_factor, supplied, static_cast<long long>(fastest), f.x_m, f.y_m,
          std::sqrt(v2_max));
      return f;
    }
    if (const double speed_limit = limits.speed_limit_m_s; speed_limit > 0) {
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double v = std::hypot(p.velocity[2 * i], p.velocity[2 * i + 1]);
        if (v <= speed_limit) continue;
        GuardFinding f = at_particle(p, static_cast<std::int64_t>(i), "kinetic_energy", v,
                                     speed_limit);
        f.message = format(
            "runaway kinetic energy at t = %.6g s: particle %lld at (%.6g, %.6g) m moves at %.4g "
            "m/s, above %.4g m/s (= max_overlap_ratio %.3g x R_min %.4g m / t_c %.4g s: a "
            "collision at this speed overlaps by more than the overlap limit)",
            t, static_cast<long long>(i), f.x_m, f.y_m, v, speed_limit, limits.max_overlap_ratio,
            limits.r_min_m, limits.critical_time_s);
        return f;
      }
    }
  }

  if (limits.max_overlap_ratio > 0) {
    const OverlapExtreme o = largest_overlap(system);
    if (o.ratio > limits.max_overlap_ratio) {
      GuardFinding f = at_particle(p, o.particle, "overlap", o.ratio, limits.max_overlap_ratio);
      f.message = format(
          "excessive overlap at t = %.6g s: particle %lld at (%.6g, %.6g) m overlaps a neighbour "
          "or a wall by %.3g of its radius, above dem.guards.max_overlap_ratio %.3g (the contacts "
          "are too soft for the load, or the time step too large)",
          t, static_cast<long long>(o.particle), f.x_m, f.y_m, o.ratio, limits.max_overlap_ratio);
      return f;
    }
  }
  return {};
}

}  // namespace rockcut::dem
