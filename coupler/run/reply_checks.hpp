// The coupler does not trust its modules' replies (a third-party fluid executable is a documented
// feature): every count, step and time a reply carries is checked before it is used, and a reply
// that does not fit is a ModuleFailure naming the module, never a crash or an endless loop.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <google/protobuf/map.h>

#include "wire/message.hpp"
#include "wire/module_client.hpp"

namespace rockcut::coupler {

/// InitReply: a particle count in 1..scene::kMaxParticles (equal to `expected_particles` if
/// given) and stability limits that are finite and positive (or 0 for a lag-only limit).
void check_init_reply(const std::string& module, const wire::InitReply& reply,
                      std::optional<std::uint64_t> expected_particles);

/// The step and time of a reply to a request for `steps` steps from (`step`, `time_s`): exactly
/// `steps` further (at most that many when a guard stopped it), and a finite time no earlier.
void check_progress(const std::string& module, std::uint64_t reply_step, double reply_time_s,
                    std::uint64_t step, double time_s, std::uint64_t steps, bool guard);

/// The names of a reply's scalars (StepReport, FluidResult): 1 to 64 letters, digits and
/// underscores each, at most kMaxReplyScalars of them. They become run.h5 dataset names and
/// summary.json keys, where "../../x" or a thousand columns would fail the output instead of
/// naming the module.
inline constexpr std::size_t kMaxReplyScalars = 1000;
void check_scalar_names(const std::string& module,
                        const google::protobuf::Map<std::string, double>& scalars);

/// The array `name` of a Frame: present, 1 to 4 components, `particles` rows. Sets `components`.
std::span<const double> frame_array(const std::string& module, const wire::Message& frame,
                                    const std::string& name, std::uint64_t particles,
                                    std::uint32_t& components);

/// The array `name` with `components` and, unless `rows` is nullopt, that many rows.
std::span<const double> checked_array(const std::string& module, const wire::Message& message,
                                      const std::string& name, std::uint32_t components,
                                      std::optional<std::uint64_t> rows);

}  // namespace rockcut::coupler
