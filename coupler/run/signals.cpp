#include "run/signals.hpp"

#include <csignal>

namespace rockcut::coupler {

namespace {
volatile std::sig_atomic_t g_stop_signal = 0;
volatile std::sig_atomic_t g_stop_count = 0;
volatile std::sig_atomic_t g_checkpoint_requests = 0;
volatile std::sig_atomic_t g_graceful = 0;
std::sig_atomic_t g_checkpoint_requests_taken = 0;  // read and written by the run loop only

extern "C" void on_stop_signal(int sig) {
  if (g_stop_signal == 0) g_stop_signal = sig;
  g_stop_count = g_stop_count + 1;
}
extern "C" void on_checkpoint_signal(int) { g_checkpoint_requests = g_checkpoint_requests + 1; }
}  // namespace

void install_stop_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // A hang-up stops the run, unless it was started to outlive its terminal (`nohup` leaves SIGHUP
  // ignored, and an ignored signal stays ignored).
  struct sigaction hangup {};
  sigaction(SIGHUP, nullptr, &hangup);
  if (hangup.sa_handler != SIG_IGN) sigaction(SIGHUP, &action, nullptr);
  signal(SIGPIPE, SIG_IGN);  // a closed stdout fails the write (EPIPE), not the run
  struct sigaction checkpoint {};
  checkpoint.sa_handler = on_checkpoint_signal;
  sigemptyset(&checkpoint.sa_mask);
  sigaction(SIGUSR1, &checkpoint, nullptr);
  // Past a file-size limit (ulimit -f) a write fails with EFBIG and the run stops with a message
  // and exit code 5, instead of the process being killed by SIGXFSZ.
  signal(SIGXFSZ, SIG_IGN);
}

int stop_signal() { return g_stop_signal; }

bool interrupt_now() { return g_stop_count >= (g_graceful ? 2 : 1); }

void set_graceful_stop(bool on) { g_graceful = on ? 1 : 0; }

bool take_checkpoint_request() {
  const std::sig_atomic_t seen = g_checkpoint_requests;
  if (seen == g_checkpoint_requests_taken) return false;
  g_checkpoint_requests_taken = seen;
  return true;
}

}  // namespace rockcut::coupler
