// The command line shared by module executables:
//   MODULE --bind ENDPOINT      serve one session on ENDPOINT (ipc://..., tcp://HOST:PORT)
// A module started by hand for `coupler run --transport tcp` binds loopback unless told otherwise.
#pragma once

#include "wire/module_server.hpp"

namespace rockcut::wire {

/// Keeps large freed blocks in the heap instead of returning them to the kernel, so the multi-MB
/// array frames of each exchange reuse pages already faulted in. bench/README.md measured 3-4x
/// fewer page faults and about 2x faster 1e6-particle inproc exchanges with these thresholds.
void tune_allocator_for_bulk_frames();

/// Parses argv, serves one session with `handler`, and returns the process exit code. User errors
/// (bad arguments, endpoint in use) are printed as one line naming the module.
int module_main(int argc, char** argv, ModuleHandler& handler);

}  // namespace rockcut::wire
