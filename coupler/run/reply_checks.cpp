#include "run/reply_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scene/particle_budget.hpp"

namespace rockcut::coupler {

void check_init_reply(const std::string& module, const wire::InitReply& reply,
                      std::optional<std::uint64_t> expected_particles) {
  const std::uint64_t n = reply.particle_count();
  if (n == 0 || n > scene::kMaxParticles) {
    throw wire::ModuleFailure(module, "InitReply announces " + std::to_string(n) +
                                          " particles (1 to " +
                                          std::to_string(scene::kMaxParticles) + " expected)");
  }
  if (expected_particles && n != *expected_particles) {
    throw wire::ModuleFailure(module, "InitReply announces " + std::to_string(n) +
                                          " particles, the DEM has " +
                                          std::to_string(*expected_particles));
  }
  for (const wire::StabilityLimit& l : reply.limits()) {
    // A limit only on a lagged coupling may be 0: N = 1 is then the only choice (an undamped DEM).
    const bool ok = std::isfinite(l.dt_max_s()) &&
                    (l.lag_only() ? l.dt_max_s() >= 0.0 : l.dt_max_s() > 0.0);
    if (!ok) {
      throw wire::ModuleFailure(module, "stability limit \"" + l.name().substr(0, 64) +
                                            "\" is not a finite positive time step");
    }
  }
}

void check_progress(const std::string& module, std::uint64_t reply_step, double reply_time_s,
                    std::uint64_t step, double time_s, std::uint64_t steps, bool guard) {
  const bool step_ok = guard ? reply_step >= step && reply_step - step <= steps
                             : reply_step >= step && reply_step - step == steps;
  if (!step_ok) {
    throw wire::ModuleFailure(module, "reported step " + std::to_string(reply_step) + " after " +
                                          std::to_string(steps) + " steps from step " +
                                          std::to_string(step));
  }
  if (!std::isfinite(reply_time_s) || reply_time_s < time_s) {
    char text[96];
    std::snprintf(text, sizeof text, "reported the time %.9g s after %.9g s", reply_time_s, time_s);
    throw wire::ModuleFailure(module, text);
  }
}

void check_scalar_names(const std::string& module,
                        const google::protobuf::Map<std::string, double>& scalars) {
  if (scalars.size() > kMaxReplyScalars) {
    throw wire::ModuleFailure(module, "sent " + std::to_string(scalars.size()) +
                                          " scalars (at most " + std::to_string(kMaxReplyScalars) +
                                          ")");
  }
  for (const auto& [name, value] : scalars) {
    const bool ok = !name.empty() && name.size() <= 64 &&
                    std::all_of(name.begin(), name.end(), [](char c) {
                      return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                             (c >= '0' && c <= '9') || c == '_';
                    });
    if (!ok) {
      std::string shown;
      for (char c : name.substr(0, 64)) shown += (c >= 32 && c < 127) ? c : '?';
      throw wire::ModuleFailure(module, "sent a scalar named \"" + shown +
                                            "\" (names are 1 to 64 letters, digits and "
                                            "underscores)");
    }
  }
}

std::span<const double> checked_array(const std::string& module, const wire::Message& message,
                                      const std::string& name, std::uint32_t components,
                                      std::optional<std::uint64_t> rows) {
  try {
    return rows ? message.array(name, components, *rows) : message.array(name, components);
  } catch (const wire::ProtocolError& e) {
    throw wire::ModuleFailure(module, std::string("sent a malformed message: ") + e.what());
  }
}

std::span<const double> frame_array(const std::string& module, const wire::Message& frame,
                                    const std::string& name, std::uint64_t particles,
                                    std::uint32_t& components) {
  components = 0;
  for (const wire::ArrayHeader& h : frame.envelope.arrays()) {
    if (h.name() == name) components = h.components();
  }
  if (components < 1 || components > 4) {
    throw wire::ModuleFailure(module, "sent a Frame without a valid \"" + name + "\" array");
  }
  return checked_array(module, frame, name, components, particles);
}

}  // namespace rockcut::coupler
