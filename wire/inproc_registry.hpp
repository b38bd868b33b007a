// Built-in modules that `coupler run --transport inproc` can start as threads.
//
// A module's service library registers its serve function here at static-initialisation time; the
// coupler looks it up by kind. The coupler never includes a module's headers: the modules stay
// separate programs that share only proto/, scene/ and wire/.
#pragma once

#include <string>

#include <zmq.hpp>

#include "rockcut/wire.pb.h"

namespace rockcut::wire {

/// Serves one session on `endpoint` (bound inside `context`); returns the exit code.
using InprocServeFn = int (*)(zmq::context_t& context, const std::string& endpoint);

/// Registers `fn` for `kind`; returns true so it can initialise a static.
bool register_inproc_module(ModuleKind kind, InprocServeFn fn);
/// The serve function for `kind`, or nullptr if none is linked in.
InprocServeFn find_inproc_module(ModuleKind kind);

}  // namespace rockcut::wire
