// The command line shared by module executables:
//   MODULE --bind ENDPOINT      serve one session on ENDPOINT (ipc://..., tcp://HOST:PORT)
// A module started by hand for `coupler run --transport tcp` binds loopback unless told otherwise.
#pragma once

#include "wire/module_server.hpp"

namespace rockcut::wire {

/// Parses argv, serves one session with `handler`, and returns the process exit code. User errors
/// (bad arguments, endpoint in use) are printed as one line naming the module.
int module_main(int argc, char** argv, ModuleHandler& handler);

}  // namespace rockcut::wire
