// The largest scene a run may ask for: a bound on the particle count, checked on the scene alone
// (before anything is allocated) by `coupler validate` and by each module on the scene it is
// sent, so a typo such as a lattice of 1e10 discs is refused up front instead of ending in an
// allocation failure or a module that stops answering.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "rockcut/scene.pb.h"

namespace rockcut::scene {

/// 36 times the paper's full-scale cut (55,177 discs); a few GB in each module.
inline constexpr std::uint64_t kMaxParticles = 2'000'000;
/// A packing file longer than this many bytes cannot hold kMaxParticles discs of sensible text.
inline constexpr std::uint64_t kMaxPackingFileBytes = kMaxParticles * 128;

/// Why `scene` would make more than kMaxParticles particles (one line naming the field), or
/// nothing. A packing file is judged by the DEM when it reads it (kMaxPackingFileBytes).
std::optional<std::string> particle_budget_problem(const rockcut::Scene& scene);
/// The same for the DEM's part alone (what the DEM is sent in Init).
std::optional<std::string> particle_budget_problem(const rockcut::Dem& dem);

}  // namespace rockcut::scene
