// The SIGINT hand-over of run_released (python/interrupt.hpp).
#include "interrupt.hpp"

#include <atomic>

#include "core/interrupt.hpp"

namespace shpb::python {

namespace {

std::atomic<bool> g_sigint{false};

extern "C" void on_sigint(int) {
  g_sigint.store(true);
  request_interrupt();
}

unsigned long g_main_thread = 0;  // set when the module is imported

bool in_main_thread() { return PyThread_get_thread_ident() == g_main_thread; }

// Python's _signal.getsignal and _signal.default_int_handler (what signal.py wraps), looked up
// once when the module is imported: an import per call cost 50 µs of every run. Kept for the
// process (never released: the interpreter may be finalising when static objects are destroyed).
py::handle g_getsignal, g_default_int_handler;

// Only in the main thread, and only where SIGINT raises KeyboardInterrupt (Python's default, and a
// notebook's while it runs a cell): a handler of the user's own runs after the work, as it would
// after any C call.
bool default_sigint_handler() { return g_getsignal(SIGINT).is(g_default_int_handler); }

}  // namespace

void set_up_interrupts() {
  g_main_thread =
      py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
  const py::module_ signal = py::module_::import("_signal");
  g_getsignal = py::object(signal.attr("getsignal")).release();
  g_default_int_handler = py::object(signal.attr("default_int_handler")).release();
}

SigintSetAside set_sigint_aside() {
  SigintSetAside s;
  s.set_aside =
      in_main_thread() && default_sigint_handler() && sigaction(SIGINT, nullptr, &s.python) == 0;
  if (s.set_aside) {
    struct sigaction ours = {};
    ours.sa_handler = on_sigint;
    sigemptyset(&ours.sa_mask);
    g_sigint.store(false);
    sigaction(SIGINT, &ours, nullptr);
  }
  return s;
}

void put_sigint_back(const SigintSetAside& s) {
  if (!s.set_aside) return;
  sigaction(SIGINT, &s.python, nullptr);
  if (g_sigint.exchange(false)) {
    clear_interrupt();
    PyErr_SetInterruptEx(SIGINT);
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // KeyboardInterrupt
  }
}

}  // namespace shpb::python
