// Interruption by SIGINT or SIGTERM (core/interrupt.hpp).
#include "core/interrupt.hpp"

#include <signal.h>

#include <atomic>
#include <csignal>

#include "core/error.hpp"

namespace shpb {

namespace {
std::atomic<bool> g_interrupted{false};  // the one global: a signal handler cannot reach others
// The first signal asks the run to stop cleanly; a second one ends it at once (default action).
extern "C" void on_signal(int sig) {
  g_interrupted.store(true);
  std::signal(sig, SIG_DFL);
}

}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  // Started with them blocked (a parent's thread that blocks them, as runtimes do), SIGTERM from
  // scancel or timeout would never arrive: taken from now on, one already pending at once.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  ::sigprocmask(SIG_UNBLOCK, &signals, nullptr);
}
bool interrupted() { return g_interrupted.load(std::memory_order_relaxed); }
void throw_if_interrupted() {
  if (interrupted()) throw Interrupted();
}
void request_interrupt() { g_interrupted.store(true); }
void clear_interrupt() { g_interrupted.store(false); }

}  // namespace shpb
