// The tool's lengths whose scene value 0 means a default derived from the cutting depth: the DEM
// builds the tool from them and the coupler's summaries and models read them, so both take them
// from here (scene.proto, message Tool).
#pragma once

#include "rockcut/scene.pb.h"

namespace rockcut::scene {

/// dem.tool.face_length_m, or three cutting depths when 0.
inline double tool_face_length_m(const rockcut::Tool& tool) {
  return tool.face_length_m() > 0 ? tool.face_length_m() : 3.0 * tool.cutting_depth_m();
}

/// dem.tool.steady_after_m, or two cutting depths when 0: where the steady part of the cut starts.
inline double tool_steady_after_m(const rockcut::Tool& tool) {
  return tool.steady_after_m() > 0 ? tool.steady_after_m() : 2.0 * tool.cutting_depth_m();
}

}  // namespace rockcut::scene
