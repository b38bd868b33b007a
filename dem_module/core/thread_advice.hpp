#pragma once
// Whether a scene's DEM thread count pays for itself: every step synchronises the threads three
// times, and a small specimen loses more to that than the threads save.
#include <cstddef>
#include <string>

namespace rockcut::dem {

/// Below this many particles per thread a second thread costs more than it saves. Measured with
/// the coupler's module processes (OMP_WAIT_POLICY=PASSIVE, each synchronisation wakes a sleeping
/// thread): dry_reduced, 647 discs and 398,311 steps, took 52 s on 2 threads against 9.7 s on 1,
/// about 106 us of synchronisation per step. One thread steps a particle in about 37 ns
/// (2.7e7 particle-steps/s in that run), so a second thread saves about 19 ns per particle and
/// step: 106 us / 19 ns is about 5,600 particles, i.e. about 2,800 per thread.
inline constexpr std::size_t kMinParticlesPerThread = 3000;

/// A one-line note for the run's log when `threads` > 1 is too many for `particles`, else "".
std::string thread_advice(std::size_t particles, int threads);

}  // namespace rockcut::dem
