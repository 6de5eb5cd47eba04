// Running library work with the GIL released, Ctrl-C as the command's SIGINT.
//
// Python runs its signal handlers in the main thread only, and only while it holds the GIL. Work
// runs in the calling thread with the GIL released, so Python threads run simulations in
// parallel. Called from the main thread, Python's SIGINT handler is set aside for the work's
// duration for one that sets the library's interrupt flag, which the library's long loops poll as
// they poll SIGINT in the command (core/interrupt.hpp); once the work has stopped, Python's
// handler is put back and given the signal (PyErr_SetInterruptEx), so Ctrl-C raises
// KeyboardInterrupt then. No thread is started: a worker thread per call cost its start and its
// wake-ups on every run (0.2–0.8 ms of a 7 ms run on a loaded machine, docs/python.md), and a
// thread kept for the process is lost in a forked child.
#pragma once

#include <pybind11/pybind11.h>
#include <signal.h>

#include <exception>
#include <optional>
#include <utility>

namespace shpb::python {

namespace py = pybind11;

// When the module is imported: the main thread, and Python's SIGINT handlers to compare with.
void set_up_interrupts();

// Python's SIGINT handler while the work runs: set aside (`set_aside`) or left as it is.
struct SigintSetAside {
  bool set_aside = false;
  struct sigaction python = {};
};
SigintSetAside set_sigint_aside();
// Python's handler put back; a Ctrl-C during the work raised in Python as KeyboardInterrupt.
void put_sigint_back(const SigintSetAside& s);

template <class F>
auto run_released(F&& work) -> decltype(work()) {
  const SigintSetAside sigint = set_sigint_aside();
  std::optional<decltype(work())> value;
  std::exception_ptr error;
  {
    py::gil_scoped_release release;
    try {
      value.emplace(work());
    } catch (...) {
      error = std::current_exception();
    }
  }
  put_sigint_back(sigint);
  if (error) std::rethrow_exception(error);
  return std::move(*value);
}

}  // namespace shpb::python
