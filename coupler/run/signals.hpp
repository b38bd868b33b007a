// Signals a run obeys. SIGINT, SIGTERM and SIGHUP (the terminal closed: a lost ssh session; not
// under `nohup`, which leaves it ignored) ask the run to stop: while the loop runs (graceful stops
// on), it completes the exchange in progress, writes a checkpoint and stops with status
// "interrupted"; a second one, or one during start-up, stops at the next wait without a checkpoint.
// SIGUSR1 (what a scheduler sends before a time limit, e.g. Slurm's --signal=B:USR1@120) asks for
// a checkpoint, after which the run carries on.
// SIGPIPE is ignored: a run whose reader went away (`coupler run ... | head`, a killed driver
// script) carries on writing its files instead of dying on its next log line, which would leave
// its modules' sockets and shared memory behind.
#pragma once

namespace rockcut::coupler {

/// Installs the handlers (idempotent).
void install_stop_signal_handlers();
/// The signal that asked to stop, or 0.
int stop_signal();
/// True when waiting must end now: a stop was asked for outside a graceful stop, or twice.
bool interrupt_now();
/// While on, the first SIGINT/SIGTERM is left to the run loop (checkpoint, then stop).
void set_graceful_stop(bool on);
/// True once per SIGUSR1 received since the last call.
bool take_checkpoint_request();

}  // namespace rockcut::coupler
