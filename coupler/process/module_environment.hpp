// The environment the coupler's module processes (transport ipc) start with: how their idle
// OpenMP threads wait (docs/performance.md, "Threads").
#pragma once

namespace rockcut::coupler {

/// Sets OMP_WAIT_POLICY=PASSIVE for the modules of a coupled scene, whose two teams take turns on
/// the same cores: a spinning team would hold the cores the other needs. A dry scene's DEM has the
/// cores to itself and keeps libgomp's default (spin briefly, then sleep), which saves a wake-up
/// at each of its barriers. An OMP_WAIT_POLICY or GOMP_SPINCOUNT of the user's wins, as does
/// the PASSIVE the tools set when they start several runs at a time on the same cores.
void prepare_module_environment(bool coupled);

}  // namespace rockcut::coupler
