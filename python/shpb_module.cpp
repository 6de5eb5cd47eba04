// The Python module's native half, shpb._shpb (README (From Python), docs/python.md): the scene as
// an editable object, and the library's own entry points of `shpb simulate` and `shpb process`
// returning their results in memory. Pure-Python conveniences (tables, save of folders, the
// commands' help) live in python/shpb/__init__.py. Nothing here re-implements a check, a formula or
// a writer: each call goes to the function the command calls.
//
// This file is the module's entry: the import-time set-up and the error classes. The bindings, one
// file a concept, are listed in bindings.hpp; values.hpp (Python values taken in), views.hpp
// (results handed out) and interrupt.hpp (work without the GIL, Ctrl-C) are their shared helpers.
#include <malloc.h>
#include <pybind11/pybind11.h>

#include <exception>
#include <string>

#include "bindings.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "interrupt.hpp"
#include "values.hpp"
#include "version.hpp"

namespace shpb::python {

namespace {

// A library error raised as `type`. Its message names files as the user gave them: a name that
// is not UTF-8 is decoded as Python decodes file names (os.fsdecode: the bytes that are not UTF-8
// as lone surrogates), so that the message is the path given, not an empty one.
void raise(const py::handle& type, const std::string& message) {
  const py::object text = py::reinterpret_steal<py::object>(
      PyUnicode_DecodeFSDefaultAndSize(message.data(), static_cast<Py_ssize_t>(message.size())));
  if (text) PyErr_SetObject(type.ptr(), text.ptr());
}

}  // namespace

}  // namespace shpb::python

PYBIND11_MODULE(_shpb, m) {
  using namespace shpb;
  using namespace shpb::python;
  m.doc() = "shpb's library: the scene, simulate and process (see the package shpb).";
  m.attr("__version__") = kVersion;
  // A run allocates and frees its bars, records and field, blocks of up to tens of MB. Above its
  // (dynamic) mmap threshold glibc serves them by mmap and returns them by munmap, so every run
  // faults its pages in afresh, and two runs in two threads wait on the process's address-space
  // lock: measured on the classic test, two threads took 1.15–1.66 × the time of one run after
  // the other. Blocks up to 32 MB (glibc's largest threshold) from the heap, and the heap kept up
  // to 256 MB free, are reused by the next run instead: 0.74–0.86 × (docs/python.md).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  set_up_interrupts();

  // Errors: the command's exit codes as exception classes. InputError is a ValueError (exit 2),
  // NumericalError a RuntimeError (exit 3), WriteError an OSError (exit 3); an interrupted run is
  // a KeyboardInterrupt (exit 130).
  static py::exception<InputError> input_error_type(m, "InputError", PyExc_ValueError);
  static py::exception<NumericalError> numerical_error_type(m, "NumericalError",
                                                            PyExc_RuntimeError);
  static py::exception<WriteError> write_error_type(m, "WriteError", PyExc_OSError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      raise(input_error_type, e.what());
    } catch (const NumericalError& e) {
      raise(numerical_error_type, e.what());
    } catch (const WriteError& e) {
      raise(write_error_type, final_names(e.what()));  // the output, not its temporary
    } catch (const Interrupted&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });

  bind_materials(m);
  bind_scene(m);
  bind_simulate(m);
  bind_process(m);
  bind_plan(m);
  bind_commands(m);
  // A value as a one-line message shows it (values.hpp), for the package's own TypeErrors.
  m.def(
      "_shown", [](const py::handle& o) { return shown(o); }, py::arg("value"));
}
