// Constants of the wire protocol (proto/rockcut/wire.proto) shared by the coupler and the modules.
#pragma once

#include <string_view>

#include "rockcut/wire.pb.h"

namespace rockcut::wire {

/// The version this build speaks; the handshake refuses any other.
inline constexpr unsigned kProtocolVersion = PROTOCOL_VERSION_CURRENT;

/// Names of the per-particle arrays that cross the wire. 2-component fields are interleaved x, y.
namespace field {
inline constexpr std::string_view kPosition = "position";            // [m], 2
inline constexpr std::string_view kVelocity = "velocity";            // [m/s], 2, at a full step
inline constexpr std::string_view kVelocityHalf = "velocity_half";   // [m/s], 2, v^{n-1/2}
inline constexpr std::string_view kDisplacement = "displacement";    // [m], 2, since last exchange
inline constexpr std::string_view kRadius = "radius";                // [m], 1
inline constexpr std::string_view kSelfStiffness = "fluid_self_stiffness";  // [Pa], 3: xx, xy, yy
inline constexpr std::string_view kForce = "force";                  // [N per m thickness], 2, total
inline constexpr std::string_view kExternalForce = "external_force"; // [N/m], 2, from the fluid
inline constexpr std::string_view kPressure = "pressure";            // [Pa], 1
/// Not per particle: one row per straight segment of the walls and the tool at the current time,
/// (ax, ay, bx, by) [m]. The fluid keeps the no-flux condition on surface particles facing them.
inline constexpr std::string_view kWallSegments = "wall_segments";   // [m], 4 per segment
}  // namespace field

/// "dem_module" / "fluid_module": how errors name a module kind.
std::string_view kind_name(ModuleKind kind);

}  // namespace rockcut::wire
