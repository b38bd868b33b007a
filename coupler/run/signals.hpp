// SIGINT and SIGTERM ask the run to stop; the run loop notices at the next wait and shuts the
// modules down with the output closed.
#pragma once

namespace rockcut::coupler {

/// Installs the handlers (idempotent).
void install_stop_signal_handlers();
/// The signal that asked to stop, or 0.
int stop_signal();

}  // namespace rockcut::coupler
