// The environment the coupler's module processes (transport ipc) start with: how their idle
// OpenMP threads wait (docs/performance.md, "Threads").
#pragma once

namespace rockcut::coupler {

/// How the modules' idle OpenMP threads wait, from how they share the cores:
/// - a dry scene's DEM has the cores to itself: libgomp's default (spin a while, then sleep),
///   which saves a wake-up at each of its barriers;
/// - a coupled scene whose modules take turns on the cores (Coupling.overlap off): a short spin
///   (GOMP_SPINCOUNT kTurnsSpinCount, tens of microseconds) that catches the next parallel region
///   of the same step and lets the cores go soon after the module's turn ends;
/// - a coupled scene whose modules overlap: OMP_WAIT_POLICY=PASSIVE, as a spinning team would
///   hold cores the other team needs.
/// An OMP_WAIT_POLICY or GOMP_SPINCOUNT of the user's wins, as does the PASSIVE the tools set when
/// they start several runs at a time on the same cores.
void prepare_module_environment(bool coupled, bool modules_take_turns);

/// Spins before an idle thread of a module taking turns sleeps (libgomp's default is 300,000).
inline constexpr const char* kTurnsSpinCount = "3000";

}  // namespace rockcut::coupler
