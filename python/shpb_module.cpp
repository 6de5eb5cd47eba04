// The Python module's native half, shpb._shpb (README (From Python), docs/python.md): the scene as
// an editable object, and the library's own entry points of `shpb simulate` and `shpb process`
// returning their results in memory. Pure-Python conveniences (tables, save of folders, the
// commands' help) live in python/shpb/__init__.py. Nothing here re-implements a check, a formula or
// a writer: each call goes to the function the command calls.
#include <malloc.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <signal.h>

#include <atomic>
#include <cmath>
#include <exception>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "app/commands.hpp"
#include "app/process.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/json_document.hpp"
#include "core/json_value.hpp"
#include "core/output_folder.hpp"
#include "core/units.hpp"
#include "model/input_limits.hpp"
#include "model/scene_validation.hpp"
#include "model/wave_travel.hpp"
#include "solver/simulation.hpp"
#include "version.hpp"

namespace py = pybind11;
using namespace shpb;

namespace {

// ---- running library work with the GIL released, Ctrl-C as the command's SIGINT --------------

// Python runs its signal handlers in the main thread only, and only while it holds the GIL. Work
// runs in the calling thread with the GIL released, so Python threads run simulations in
// parallel. Called from the main thread, Python's SIGINT handler is set aside for the work's
// duration for one that sets the library's interrupt flag, which the library's long loops poll as
// they poll SIGINT in the command (core/output_folder.hpp); once the work has stopped, Python's
// handler is put back and given the signal (PyErr_SetInterruptEx), so Ctrl-C raises
// KeyboardInterrupt then. No thread is started: a worker thread per call cost its start and its
// wake-ups on every run (0.2–0.8 ms of a 7 ms run on a loaded machine, docs/python.md), and a
// thread kept for the process is lost in a forked child.
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

template <class F>
auto run_released(F&& work) -> decltype(work()) {
  struct sigaction python = {};
  const bool set_aside =
      in_main_thread() && default_sigint_handler() && sigaction(SIGINT, nullptr, &python) == 0;
  if (set_aside) {
    struct sigaction ours = {};
    ours.sa_handler = on_sigint;
    sigemptyset(&ours.sa_mask);
    g_sigint.store(false);
    sigaction(SIGINT, &ours, nullptr);
  }
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
  if (set_aside) {
    sigaction(SIGINT, &python, nullptr);
    if (g_sigint.exchange(false)) {
      clear_interrupt();
      PyErr_SetInterruptEx(SIGINT);
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // KeyboardInterrupt
    }
  }
  if (error) std::rethrow_exception(error);
  return std::move(*value);
}

// A library error raised as `type`. Its message names files as the user gave them: a name that
// is not UTF-8 is decoded as Python decodes file names (os.fsdecode: the bytes that are not UTF-8
// as lone surrogates), so that the message is the path given, not an empty one.
void raise(const py::handle& type, const std::string& message) {
  const py::object text = py::reinterpret_steal<py::object>(
      PyUnicode_DecodeFSDefaultAndSize(message.data(), static_cast<Py_ssize_t>(message.size())));
  if (text) PyErr_SetObject(type.ptr(), text.ptr());
}

// ---- numpy views ------------------------------------------------------------------------------

// A read-only numpy array over a vector that `owner` (a Python object holding it) keeps alive:
// no copy of the library's time series.
py::array_t<double> view(const std::vector<double>& v, py::handle owner) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()), v.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// Columns of a TimeSeries as {"time_s": ..., name: ...}, in the CSV's order.
py::dict series(const TimeSeries& s, py::handle owner) {
  py::dict d;
  d["time_s"] = view(s.time_s, owner);
  for (std::size_t c = 0; c < s.columns.size(); ++c)
    d[s.columns[c].c_str()] = view(s.values[c], owner);
  return d;
}

// summary.json's values as Python objects, keys in the file's order (what json.loads of the
// file gives, without writing and parsing the text).
py::object json_to_python(const nlohmann::ordered_json& j) {
  switch (j.type()) {
    case nlohmann::ordered_json::value_t::null:
      return py::none();
    case nlohmann::ordered_json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::ordered_json::value_t::number_integer:
      return py::int_(j.get<std::int64_t>());
    case nlohmann::ordered_json::value_t::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case nlohmann::ordered_json::value_t::number_float: {
      const double x = j.get<double>();  // the file holds null for a non-finite number
      return std::isfinite(x) ? py::object(py::float_(x)) : py::object(py::none());
    }
    case nlohmann::ordered_json::value_t::string:
      return py::str(j.get_ref<const std::string&>());
    case nlohmann::ordered_json::value_t::array: {
      py::list l(j.size());
      for (std::size_t i = 0; i < j.size(); ++i) l[i] = json_to_python(j[i]);
      return l;
    }
    case nlohmann::ordered_json::value_t::object: {
      py::dict d;
      for (const auto& [key, value] : j.items()) d[py::str(key)] = json_to_python(value);
      return d;
    }
    default:  // binary and discarded values: summary.json holds none
      throw std::logic_error("summary value of an unexpected JSON type");
  }
}

// ---- the scene --------------------------------------------------------------------------------

// Python text as UTF-8 for a message: a lone surrogate (a file name that is not UTF-8, as
// os.fsdecode gives it) as its \udcff escape instead of a failed conversion.
std::string message_text(const py::handle& s) {
  return py::bytes(py::str(s).attr("encode")("utf-8", "backslashreplace")).cast<std::string>();
}

// An object as a message shows it: its repr on one line (a DataFrame's repr has many: its type).
std::string shown(const py::handle& o) {
  const std::string r = message_text(py::repr(o));
  if (r.find('\n') == std::string::npos) return r;
  return "a " + message_text(py::type::of(o).attr("__name__"));
}

// The JSON value of an object json.dumps cannot write itself: a numpy scalar or 0-d array of a
// number, bool or text (its value; a float16 or long double as the nearest double), a path (its
// text). nullopt for anything else: complex numbers, dates, arrays of several values (a numpy
// array is no JSON list: `.tolist()` makes it one), masked values, bytes, ...
std::optional<py::object> json_value_of(const py::handle& o) {
  if (py::module_::import("sys").attr("modules").contains("numpy")) {
    const py::module_ np = py::module_::import("numpy");
    const bool scalar = py::isinstance(o, np.attr("generic")) ||
                        (py::type::of(o).is(np.attr("ndarray")) && o.attr("ndim").cast<int>() == 0);
    if (scalar) {
      const char kind = o.attr("dtype").attr("kind").cast<std::string>()[0];
      if (kind == 'f') return py::float_(py::reinterpret_borrow<py::object>(o));
      if (std::string("iubUO").find(kind) != std::string::npos) return o.attr("item")();
      return std::nullopt;
    }
  }
  if (py::hasattr(o, "__fspath__")) {
    py::object text = py::module_::import("os").attr("fspath")(o);
    if (py::isinstance<py::str>(text)) return text;
  }
  return std::nullopt;
}

// A number handed to the module (a keyword argument, an edited value) taken as a scene value is
// (json_value_of, docs/python.md): a Python int or float, a numpy scalar or 0-d array by its value.
// Anything else is a TypeError naming `name`: a numpy array of one or more values (a 1-element
// one was read as its value, which a scene dict refuses), a bool, text, a list.
template <class T>
T number(const py::handle& o, const std::string& name,
         const char* expected = std::is_integral_v<T> ? "expected a whole number"
                                                      : "expected a number") {
  py::object value = py::reinterpret_borrow<py::object>(o);
  if (const auto v = json_value_of(o)) value = *v;
  if (!py::isinstance<py::bool_>(value) &&
      (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))) {
    try {
      return value.cast<T>();  // a float as a whole number, a count below 0: refused below
    } catch (const py::cast_error&) {
    }
  }
  throw py::type_error(name + ": " + shown(o) + ": " + expected);
}
template <class T>
std::optional<T> optional_number(const py::handle& o, const std::string& name) {
  if (o.is_none()) return std::nullopt;
  return number<T>(o, name);
}

// The first value of `o` json.dumps refuses, with its JSON path as the scene reader writes paths
// (core/json_value.hpp) and how it is shown: a key of no JSON type, a NaN or infinite number, an
// object of no JSON type, or nesting deeper than the reader takes (a dict that holds itself is
// nested without end), refused as the reader refuses it.
struct NotJson {
  std::string path, value;
  const char* expected =
      "expected a finite number, a string, true, false, null, a list or a dict "
      "(NaN and infinity are not JSON)";
};
std::optional<NotJson> first_not_json(const py::handle& o, const std::string& path,
                                      const std::string& file, int depth = 0) {
  const bool container =
      py::isinstance<py::dict>(o) || py::isinstance<py::list>(o) || py::isinstance<py::tuple>(o);
  if (container) ++depth;
  if (depth > kMaxJsonDepth) throw too_deep(file, path);
  if (py::isinstance<py::dict>(o)) {
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(o)) {
      const std::string child = json_child_path(path, message_text(key));
      const bool number_key = py::isinstance<py::int_>(key) || py::isinstance<py::float_>(key);
      if (!(key.is_none() || py::isinstance<py::str>(key) || number_key) ||
          (py::isinstance<py::float_>(key) && !std::isfinite(key.cast<double>())))
        return NotJson{child, "key " + shown(key), "expected a key that is a string or a number"};
      if (auto bad = first_not_json(value, child, file, depth)) return bad;
    }
    return std::nullopt;
  }
  if (py::isinstance<py::list>(o) || py::isinstance<py::tuple>(o)) {
    std::size_t i = 0;
    for (const auto& item : o)
      if (auto bad = first_not_json(item, json_element_path(path, i++), file, depth)) return bad;
    return std::nullopt;
  }
  if (py::isinstance<py::float_>(o) && !std::isfinite(o.cast<double>()))
    return NotJson{path, shown(o)};
  if (o.is_none() || py::isinstance<py::str>(o) || py::isinstance<py::bool_>(o) ||
      py::isinstance<py::int_>(o) || py::isinstance<py::float_>(o))
    return std::nullopt;
  if (const auto value = json_value_of(o)) {
    if (py::isinstance<py::float_>(*value) && !std::isfinite(value->cast<double>()))
      return NotJson{path, shown(o)};
    return first_not_json(*value, path, file, depth + 1);  // a 0-d object array may hold itself
  }
  return NotJson{path, shown(o)};
}

// Python strings, ints and floats, nested in dicts and lists, as JSON text (json.dumps; numpy
// scalars by their value). NaN and infinity are not JSON: refused as the scene file would be, in
// the reader's one line naming `file`, the JSON path and the value.
std::string dict_to_json_text(const py::object& d, const std::filesystem::path& file) {
  py::object json = py::module_::import("json");
  py::object to_value = py::cpp_function([](py::object o) -> py::object {
    if (const auto value = json_value_of(o)) return *value;
    throw py::type_error("not JSON");  // located by first_not_json
  });
  try {
    return json.attr("dumps")(d, py::arg("allow_nan") = false, py::arg("default") = to_value)
        .cast<std::string>();
  } catch (py::error_already_set& e) {
    // A circular reference is a ValueError of json.dumps, nesting beyond Python's recursion
    // limit a RecursionError.
    if (!e.matches(PyExc_ValueError) && !e.matches(PyExc_TypeError) &&
        !e.matches(PyExc_RecursionError))
      throw;
    if (const auto bad = first_not_json(d, "", file.string()))
      throw input_error(file.string(), bad->path.empty() ? "(top level)" : bad->path, bad->value,
                        bad->expected);
    throw input_error(file.string(), "", "", "not JSON: " + message_text(e.value()));
  }
}

// The bar named `name` or at index `i` (negative from the end, as Python lists).
BarSpec& bar_of(Scene& s, const py::object& key) {
  if (py::isinstance<py::str>(key)) {
    const std::string name = message_text(key);  // a lone surrogate names no bar
    for (auto& b : s.bars)
      if (b.name == name) return b;
    throw py::key_error("no bar named \"" + name + "\" in scene " + s.name);
  }
  // An index as a list takes one (an int, a numpy integer): anything else is a TypeError.
  if (!PyIndex_Check(key.ptr()))
    throw py::type_error("bar: " + shown(key) + ": expected a bar's name or index");
  Py_ssize_t i = PyNumber_AsSsize_t(key.ptr(), PyExc_IndexError);
  if (i == -1 && PyErr_Occurred()) throw py::error_already_set();
  const auto n = static_cast<Py_ssize_t>(s.bars.size());
  if (i < 0) i += n;
  if (i < 0 || i >= n) throw py::index_error("bar index out of range");
  return s.bars[static_cast<std::size_t>(i)];
}

std::optional<double> tolerance_value(const py::object& t) {
  if (t.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(t)) {
    const std::string text = message_text(t);  // a lone surrogate: no quantity, refused below
    try {
      return parse_quantity(text, Dimension::kDimensionless);
    } catch (const std::invalid_argument&) {
      throw input_error("tolerance", "", "\"" + text + "\"",
                        "expected a gauge error such as \"1 %\" or 0.01");
    }
  }
  return number<double>(t, "tolerance", "expected a gauge error such as \"1 %\" or 0.01");
}

// Some text per edited field: name=value, SI units in the names (the attributes' own names).
std::string fields(std::initializer_list<std::pair<const char*, double>> values) {
  std::string text;
  for (const auto& [name, value] : values)
    text += (text.empty() ? "" : ", ") + std::string(name) + "=" + format_double(value);
  return text;
}

RunOverrides overrides_of(const py::object& tolerance, const std::optional<std::string>& contact,
                          const std::optional<std::string>& stepping, const py::object& courant,
                          const py::object& threads) {
  RunOverrides o;
  o.tolerance = tolerance_value(tolerance);
  if (contact) {
    o.contact = contact_method_from_string(*contact);
    if (!o.contact || *o.contact == ContactMethod::kBonded)
      throw input_error("contact", "", "\"" + *contact + "\"",
                        "expected penalty, bipenalty or localized-bipenalty");
  }
  if (stepping) {
    o.stepping = stepping_from_string(*stepping);
    if (!o.stepping)
      throw input_error("stepping", "", "\"" + *stepping + "\"", "expected asynchronous or global");
  }
  o.courant = optional_number<double>(courant, "courant");
  o.threads = number<int>(threads, "threads");
  o.quiet = true;
  return o;
}

// An edited number meets the range the scene reader gives its JSON key (model/scene_reader.cpp,
// model/material_reader.cpp), so that a run never starts from a value no scene file could hold.
enum class Range { kFinite, kPositive, kNonNegative, kFraction };

template <class T>
auto checked(double T::*field, const char* name, Range range) {
  return [field, name, range](T& object, const py::object& value) {
    const double x = number<double>(value, name);
    const bool ok =
        std::isfinite(x) && (range == Range::kFinite || (range == Range::kPositive && x > 0) ||
                             (range == Range::kNonNegative && x >= 0) ||
                             (range == Range::kFraction && x >= 0 && x <= 1));
    if (!ok)
      throw input_error("scene edit", name, format_double(x),
                        range == Range::kPositive      ? "must be > 0"
                        : range == Range::kNonNegative ? "must be >= 0"
                        : range == Range::kFraction    ? "must be in [0, 1]"
                                                       : "must be a finite number");
    object.*field = x;
  };
}

// A Johnson-Cook temperature edit: its range, then the readers' rules between the temperatures
// (model/input_limits.hpp), so that the homologous temperature stays the one a file could give.
auto jc_temperature(double JohnsonCookParams::*field, const char* name) {
  return [field, name](JohnsonCookParams& o, const py::object& x) {
    JohnsonCookParams edited = o;
    checked(field, name, Range::kPositive)(edited, x);
    std::string what =
        melting_temperature_problem(edited.melting_temperature_K, edited.room_temperature_K);
    if (!what.empty())
      what = "melting_temperature_K " + format_double(edited.melting_temperature_K) + " " + what;
    else if (what = test_temperature_problem(edited.initial_temperature_K,
                                             edited.melting_temperature_K);
             !what.empty())
      what = "initial_temperature_K " + format_double(edited.initial_temperature_K) + " " + what;
    if (!what.empty()) throw input_error("scene edit", name, format_double(edited.*field), what);
    o = edited;
  };
}

// A material's parameters of one law, its attribute group (material.bilinear,
// material.johnson_cook): read on any material, set only on a material of that law, where the
// scene reader takes them (model/material_reader.cpp); on another one an edit was kept unused.
template <class P>
struct LawParams {
  MaterialSpec* material;
};
template <class P>
P& params_of(const LawParams<P>& l) {
  if constexpr (std::is_same_v<P, BilinearParams>)
    return l.material->bilinear;
  else
    return l.material->johnson_cook;
}
template <class P>
constexpr std::pair<MaterialModel, const char*> law_of() {
  if constexpr (std::is_same_v<P, BilinearParams>)
    return {MaterialModel::kBilinear, "bilinear"};
  else
    return {MaterialModel::kJohnsonCook, "johnson_cook"};
}
template <class P, class T>
auto law_get(T P::*field) {
  return [field](const LawParams<P>& l) { return params_of(l).*field; };
}
// The edit `set` of the attribute `name` (group.attribute), refused unless the material's law is
// the group's.
template <class P, class Set>
auto law_set(const char* name, Set set) {
  return [name, set](LawParams<P>& l, const py::object& x) {
    const auto [law, group] = law_of<P>();
    if (l.material->model != law)
      throw input_error("scene edit", name, shown(x),
                        "material \"" + l.material->name + "\" is " +
                            std::string(to_string(l.material->model)) + ": " + group +
                            ".* applies only to a " + std::string(to_string(law)) + " material");
    set(params_of(l), x);
  };
}
template <class P>
auto law_set(double P::*field, const char* name, Range range) {
  return law_set<P>(name, checked(field, name, range));
}

// A bar's length edit: its range, then its gauges on it, as the scene reader places them.
void set_length(BarSpec& b, const py::object& value) {
  BarSpec edited = b;
  checked(&BarSpec::length_m, "bar.length_m", Range::kPositive)(edited, value);
  const double x = edited.length_m;
  for (const auto& g : b.gauges)
    if (const std::string what = gauge_position_problem(g.position_m, x); !what.empty())
      throw input_error(
          "scene edit", "bar.length_m", format_double(x),
          "gauge \"" + g.name + "\" at " + format_double(g.position_m) + " m " + what);
  b.length_m = x;
}

// ---- results ----------------------------------------------------------------------------------

struct Simulation {
  Scene scene;  // as run: overrides applied, meshes chosen
  SimulationResult result;
};

struct Processing {
  Scene scene;
  ProcessOutcome outcome;
};

}  // namespace

PYBIND11_MODULE(_shpb, m) {
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
  g_main_thread =
      py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
  const py::module_ signal = py::module_::import("_signal");
  g_getsignal = py::object(signal.attr("getsignal")).release();
  g_default_int_handler = py::object(signal.attr("default_int_handler")).release();

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

  // Material parameters, SI units in the names (docs/scene-format.md gives the JSON keys).
  using JohnsonCook = LawParams<JohnsonCookParams>;
  using JC = JohnsonCookParams;
  py::class_<JohnsonCook>(m, "JohnsonCook")
      .def_property("A_Pa", law_get(&JC::A_Pa),
                    law_set(&JC::A_Pa, "johnson_cook.A_Pa", Range::kNonNegative))
      .def_property("B_Pa", law_get(&JC::B_Pa),
                    law_set(&JC::B_Pa, "johnson_cook.B_Pa", Range::kNonNegative))
      .def_property("n", law_get(&JC::n), law_set(&JC::n, "johnson_cook.n", Range::kFraction))
      .def_property("C", law_get(&JC::C), law_set(&JC::C, "johnson_cook.C", Range::kFinite))
      .def_property("reference_strain_rate_1_s", law_get(&JC::reference_strain_rate_1_s),
                    law_set(&JC::reference_strain_rate_1_s,
                            "johnson_cook.reference_strain_rate_1_s", Range::kPositive))
      .def_property("m", law_get(&JC::m), law_set(&JC::m, "johnson_cook.m", Range::kPositive))
      .def_property(
          "room_temperature_K", law_get(&JC::room_temperature_K),
          law_set<JC>("johnson_cook.room_temperature_K",
                      jc_temperature(&JC::room_temperature_K, "johnson_cook.room_temperature_K")))
      .def_property("melting_temperature_K", law_get(&JC::melting_temperature_K),
                    law_set<JC>("johnson_cook.melting_temperature_K",
                                jc_temperature(&JC::melting_temperature_K,
                                               "johnson_cook.melting_temperature_K")))
      .def_property("initial_temperature_K", law_get(&JC::initial_temperature_K),
                    law_set<JC>("johnson_cook.initial_temperature_K",
                                jc_temperature(&JC::initial_temperature_K,
                                               "johnson_cook.initial_temperature_K")))
      .def_property(
          "specific_heat_J_kgK", law_get(&JC::specific_heat_J_kgK),
          law_set(&JC::specific_heat_J_kgK, "johnson_cook.specific_heat_J_kgK", Range::kPositive))
      .def_property("taylor_quinney", law_get(&JC::taylor_quinney),
                    law_set(&JC::taylor_quinney, "johnson_cook.taylor_quinney", Range::kFraction))
      .def_property("adiabatic", law_get(&JC::adiabatic),
                    law_set<JC>("johnson_cook.adiabatic",
                                [](JC& o, const py::object& x) { o.adiabatic = x.cast<bool>(); }))
      .def("__repr__", [](const JohnsonCook& l) {
        const JC& o = params_of(l);
        return "<shpb.JohnsonCook " +
               fields({{"A_Pa", o.A_Pa},
                       {"B_Pa", o.B_Pa},
                       {"n", o.n},
                       {"C", o.C},
                       {"reference_strain_rate_1_s", o.reference_strain_rate_1_s},
                       {"m", o.m},
                       {"room_temperature_K", o.room_temperature_K},
                       {"melting_temperature_K", o.melting_temperature_K}}) +
               (o.adiabatic ? ", adiabatic" : "") + ">";
      });
  using Bilinear = LawParams<BilinearParams>;
  py::class_<Bilinear>(m, "Bilinear")
      .def_property(
          "yield_stress_Pa", law_get(&BilinearParams::yield_stress_Pa),
          law_set(&BilinearParams::yield_stress_Pa, "bilinear.yield_stress_Pa", Range::kPositive))
      .def_property("tangent_modulus_Pa", law_get(&BilinearParams::tangent_modulus_Pa),
                    law_set(&BilinearParams::tangent_modulus_Pa, "bilinear.tangent_modulus_Pa",
                            Range::kNonNegative))
      .def("__repr__", [](const Bilinear& l) {
        const BilinearParams& o = params_of(l);
        return "<shpb.Bilinear " +
               fields({{"yield_stress_Pa", o.yield_stress_Pa},
                       {"tangent_modulus_Pa", o.tangent_modulus_Pa}}) +
               ">";
      });
  py::class_<MaterialSpec>(m, "Material")
      .def_readonly("name", &MaterialSpec::name)
      .def_property_readonly("model",
                             [](const MaterialSpec& s) { return std::string(to_string(s.model)); })
      .def_property(
          "density_kg_m3", [](const MaterialSpec& o) { return o.density_kg_m3; },
          checked(&MaterialSpec::density_kg_m3, "material.density_kg_m3", Range::kPositive))
      .def_property(
          "youngs_modulus_Pa", [](const MaterialSpec& o) { return o.youngs_modulus_Pa; },
          checked(&MaterialSpec::youngs_modulus_Pa, "material.youngs_modulus_Pa", Range::kPositive))
      .def_property(
          "poisson_ratio", [](const MaterialSpec& o) { return o.poisson_ratio; },
          [](MaterialSpec& o, const py::object& value) {
            const double x = number<double>(value, "material.poisson_ratio");
            if (!(x > kPoissonRatioAbove && x < kPoissonRatioBelow))
              throw input_error("scene edit", "material.poisson_ratio", format_double(x),
                                "must be in (" + format_double(kPoissonRatioAbove) + ", " +
                                    format_double(kPoissonRatioBelow) + ")");
            o.poisson_ratio = x;
          })
      // The group holds its material alive. A property applies no call policy given beside its
      // getter (pybind11 takes only the function's record from it), so the getter carries it.
      .def_property_readonly(
          "bilinear",
          py::cpp_function([](MaterialSpec& s) { return Bilinear{&s}; }, py::keep_alive<0, 1>()))
      .def_property_readonly(
          "johnson_cook",
          py::cpp_function([](MaterialSpec& s) { return JohnsonCook{&s}; }, py::keep_alive<0, 1>()))
      .def_property_readonly("wave_speed_m_s", &MaterialSpec::wave_speed_m_s)
      .def("__repr__", [](const MaterialSpec& s) {
        return "<shpb.Material " + s.name + " (" + std::string(to_string(s.model)) + "): " +
               fields({{"density_kg_m3", s.density_kg_m3},
                       {"youngs_modulus_Pa", s.youngs_modulus_Pa},
                       {"poisson_ratio", s.poisson_ratio},
                       {"wave_speed_m_s", s.wave_speed_m_s()}}) +
               ">";
      });
  py::class_<BarSpec>(m, "Bar")
      .def_readonly("name", &BarSpec::name)
      .def_readonly("material", &BarSpec::material, py::return_value_policy::reference_internal)
      .def_property(
          "length_m", [](const BarSpec& o) { return o.length_m; }, &set_length)
      .def_readonly("area_m2", &BarSpec::area_m2)
      .def_readonly("diameter_m", &BarSpec::diameter_m)
      .def_property(
          "velocity_m_s", [](const BarSpec& o) { return o.velocity_m_s; },
          checked(&BarSpec::velocity_m_s, "bar.velocity_m_s", Range::kFinite))
      .def_property(
          "elements", [](const BarSpec& b) { return b.elements; },
          [](BarSpec& b, const py::object& value) {
            const int n = number<int>(value, "bar.elements");
            if (n < 0 || n > kMaxElements)
              throw input_error("scene edit", "bar.elements", std::to_string(n),
                                "must be in [1, " + std::to_string(kMaxElements) +
                                    "], or 0 for the automatic mesh");
            b.elements = n;
          })
      .def_property(
          "gap_m", [](const BarSpec& o) { return o.gap_m; },
          checked(&BarSpec::gap_m, "bar.gap_m", Range::kNonNegative))
      .def_property_readonly("gauges",
                             [](const BarSpec& b) {
                               py::dict d;
                               for (const auto& g : b.gauges) d[g.name.c_str()] = g.position_m;
                               return d;
                             })
      .def("__repr__", [](const BarSpec& b) {
        return "<shpb.Bar " + b.name + ": " + b.material.name + ", " + format_double(b.length_m) +
               " m, " + format_double(b.velocity_m_s) + " m/s>";
      });
  // Edits (e.g. scene.striker.velocity_m_s = 12) act on the scene in memory; a run checks the
  // edited scene with the one validation every command applies (model/scene_validation.hpp).
  // The scene's file made absolute when read: its relative paths (measurement data, read when the
  // scene is processed) then resolve as they did when it was loaded, whatever os.chdir (a
  // notebook's %cd) did in between.
  py::class_<Scene>(m, "Scene")
      .def_static(
          "load",
          [](const std::filesystem::path& file) {
            // An empty path (std::filesystem::absolute throws on it) is the reader's to refuse.
            return read_scene(file.empty() ? file : std::filesystem::absolute(file));
          },
          py::arg("path"))
      .def_static(
          "from_dict",
          [](const py::object& d, const std::filesystem::path& file) {
            if (file.empty())
              throw input_error("file", "", "\"\"",
                                "expected the path the dict's relative paths are written from, "
                                "such as \"scene.json\"");
            const std::filesystem::path anchored = std::filesystem::absolute(file);
            return read_scene_text(dict_to_json_text(d, anchored), anchored);
          },
          py::arg("d"), py::arg("file") = std::filesystem::path("scene.json"))
      .def_readwrite("name", &Scene::name)
      .def_property_readonly("file", [](const Scene& s) { return s.file; })
      .def_property_readonly(
          "bars",
          [](py::object self) {
            Scene& s = self.cast<Scene&>();
            py::list l;
            for (auto& b : s.bars)
              l.append(py::cast(&b, py::return_value_policy::reference_internal, self));
            return l;
          })
      .def("bar", &bar_of, py::arg("key"), py::return_value_policy::reference_internal)
      .def_property_readonly("specimen",
                             [](py::object self) -> py::object {
                               Scene& s = self.cast<Scene&>();
                               if (!s.specimen) return py::none();
                               return py::cast(&s.bars[*s.specimen],
                                               py::return_value_policy::reference_internal, self);
                             })
      .def_property_readonly("striker",
                             [](py::object self) -> py::object {
                               Scene& s = self.cast<Scene&>();
                               const auto i = striker_bar(s);
                               if (!i) return py::none();
                               return py::cast(&s.bars[*i],
                                               py::return_value_policy::reference_internal, self);
                             })
      .def_property(
          "tolerance", [](const Scene& s) { return s.simulation.tolerance; },
          [](Scene& s, const py::object& t) {
            // Refused when set, as the other edits, with the one rule of the scene's key and
            // --tolerance (model/scene_validation.hpp).
            const auto value = tolerance_value(t);
            if (value)
              if (const std::string what = tolerance_problem(*value); !what.empty())
                throw input_error("scene edit", "simulation.tolerance",
                                  format_double(*value * 100) + " %", what);
            s.simulation.tolerance = value;
          })
      .def_property(
          "duration_s", [](const Scene& s) { return s.simulation.duration_s; },
          [](Scene& s, const py::object& value) {
            const auto t = optional_number<double>(value, "duration_s");
            if (t && !(std::isfinite(*t) && *t > 0))
              throw input_error("scene edit", "duration_s", format_double(*t), "must be > 0");
            s.simulation.duration_s = t;
          })
      .def(
          "validate",
          [](const Scene& s, const py::object& tolerance) {
            Scene copy = s;
            apply_overrides(overrides_of(tolerance, {}, {}, py::none(), py::int_(0)), copy);
          },
          py::arg("tolerance") = py::none())
      .def("copy", [](const Scene& s) { return Scene(s); })
      .def("__copy__", [](const Scene& s) { return Scene(s); })
      .def("__deepcopy__", [](const Scene& s, py::object) { return Scene(s); })
      .def("__repr__", [](const Scene& s) {
        return "<shpb.Scene " + s.name + ": " + std::to_string(s.bars.size()) + " bars>";
      });

  py::class_<Simulation, std::shared_ptr<Simulation>>(m, "_Simulation")
      .def_property_readonly("scene", [](const Simulation& s) { return s.scene; })
      .def_property_readonly(
          "gauges",
          [](py::object self) { return series(self.cast<Simulation&>().result.gauges, self); })
      .def_property_readonly(
          "interfaces",
          [](py::object self) { return series(self.cast<Simulation&>().result.interfaces, self); })
      .def_property_readonly("specimen",
                             [](py::object self) -> py::object {
                               const Simulation& s = self.cast<Simulation&>();
                               if (!s.scene.specimen) return py::none();
                               return series(s.result.specimen, self);
                             })
      .def_property_readonly(
          "energy",
          [](py::object self) { return series(self.cast<Simulation&>().result.energy, self); })
      .def_property_readonly("field",
                             [](py::object self) {
                               const FieldGrid& f = self.cast<Simulation&>().result.field;
                               py::array_t<double> stress = view(f.stress_Pa, self);
                               py::dict d;
                               d["time_s"] = view(f.time_s, self);
                               d["x_m"] = view(f.x_m, self);
                               d["stress_Pa"] =
                                   stress.reshape({static_cast<py::ssize_t>(f.time_s.size()),
                                                   static_cast<py::ssize_t>(f.x_m.size())});
                               return d;
                             })
      .def_property_readonly(
          "summary",
          [](const Simulation& s) { return json_to_python(simulation_summary(s.result, s.scene)); })
      .def_property_readonly("stable", [](const Simulation& s) { return s.result.stable; })
      .def_property_readonly("failure", [](const Simulation& s) { return s.result.failure; })
      .def_property_readonly("warnings", [](const Simulation& s) { return s.result.warnings; })
      .def_property_readonly("wall_time_s",
                             [](const Simulation& s) { return s.result.wall_time_s; })
      .def(
          "save",
          [](const Simulation& s, const std::filesystem::path& dir) {
            // As run_simulate (app/simulate.cpp): the folder's checks, the writers, one commit.
            run_released([&] {
              OutputFolder out(dir, "simulate", scene_inputs(s.scene, false));
              write_simulation_outputs(s.result, s.scene, out.path());
              out.commit();
              return 0;
            });
          },
          py::arg("dir"));

  m.def(
      "_simulate",
      [](const Scene& scene, const py::object& tolerance, const std::optional<std::string>& contact,
         const std::optional<std::string>& stepping, const py::object& courant,
         const py::object& threads, bool full_model) {
        auto s = std::make_shared<Simulation>();
        s->scene = scene;
        const RunOverrides overrides = overrides_of(tolerance, contact, stepping, courant, threads);
        SimulationOptions options;
        options.full_model = full_model;
        options.cancel = [] { return interrupted(); };
        // The meshes a tolerance chooses are searched here too (tens of ms): without the GIL.
        s->result = run_released([&] {
          apply_overrides(overrides, s->scene);
          return simulate(s->scene, options);
        });
        return s;
      },
      py::arg("scene"), py::arg("tolerance") = py::none(), py::arg("contact") = py::none(),
      py::arg("stepping") = py::none(), py::arg("courant") = py::none(),
      py::arg("threads") = py::int_(0), py::arg("full_model") = false);

  py::class_<Processing, std::shared_ptr<Processing>>(m, "_Processing")
      .def_property_readonly("scene", [](const Processing& p) { return p.scene; })
      .def_property_readonly("raw_signals",
                             [](py::object self) {
                               const GaugeSignals& g = self.cast<Processing&>().outcome.signals;
                               py::dict d;
                               d["time_s"] = view(g.time_s, self);
                               for (std::size_t i = 0; i < g.gauges.size(); ++i)
                                 d[g.gauges[i].c_str()] = view(g.strain[i], self);
                               return d;
                             })
      .def_property_readonly("pulses",
                             [](py::object self) {
                               const ProcessingResult& r = self.cast<Processing&>().outcome.result;
                               py::dict d;
                               d["time_s"] = view(r.time_s, self);
                               d["incident"] = view(r.incident, self);
                               d["reflected"] = view(r.reflected, self);
                               d["transmitted"] = view(r.transmitted, self);
                               return d;
                             })
      .def_property_readonly("curve",
                             [](py::object self) {
                               // curve.csv's columns and rows (up to the end of loading), in its
                               // order.
                               const ProcessingResult& r = self.cast<Processing&>().outcome.result;
                               const auto rows = static_cast<py::ssize_t>(r.loading_end);
                               py::dict d;
                               const auto columns = curve_columns(self.cast<Processing&>().outcome);
                               for (const auto& [name, v] : columns)
                                 d[name] = view(*v, self)[py::slice(0, rows, 1)];
                               return d;
                             })
      .def_property_readonly(
          "summary",
          [](const Processing& p) {
            return json_to_python(process_summary(p.outcome, p.scene.file.string()));
          })
      .def_property_readonly("warnings", [](const Processing& p) { return p.outcome.warnings; })
      .def(
          "save",
          [](const Processing& p, const std::filesystem::path& dir) {
            run_released([&] {
              write_process_outputs(p.outcome, p.scene, p.scene.file.string(), dir);
              return 0;
            });
          },
          py::arg("dir"));

  m.def(
      "_process",
      [](const Scene& scene, const std::optional<std::filesystem::path>& signals,
         const py::object& draws, const py::object& seed) {
        auto p = std::make_shared<Processing>();
        p->scene = scene;
        MonteCarloOptions monte_carlo;
        monte_carlo.draws = number<std::size_t>(draws, "draws");
        monte_carlo.seed = number<std::uint64_t>(seed, "seed");
        p->outcome = run_released([&] {
          ProcessOutcome o = process_scene(p->scene, signals, false);
          add_uncertainty(p->scene, monte_carlo, o);
          return o;
        });
        if (!p->outcome.failure.empty()) throw NumericalError(p->outcome.failure);
        return p;
      },
      py::arg("scene"), py::arg("signals") = py::none(), py::arg("draws") = py::int_(kDefaultDraws),
      py::arg("seed") = py::int_(kDefaultSeed));

  // compare, study, fit and dispersion: the command's own function, writing its folder (or file)
  // where the Python side reads it back (python/shpb/__init__.py). The exit code is returned: 3
  // is a result written with a numerical failure said in its summary.
  m.def(
      "_compare",
      [](const std::filesystem::path& scene, const std::filesystem::path& output,
         const py::object& tolerance, const std::optional<std::string>& contact,
         const std::optional<std::string>& stepping, const py::object& courant,
         const py::object& threads, bool dispersion, const py::object& striker_velocity) {
        CompareArgs a{scene, output, overrides_of(tolerance, contact, stepping, courant, threads),
                      dispersion, optional_number<double>(striker_velocity, "striker_velocity")};
        return run_released([&] { return run_compare(a); });
      },
      py::arg("scene"), py::arg("output"), py::arg("tolerance"), py::arg("contact"),
      py::arg("stepping"), py::arg("courant"), py::arg("threads"), py::arg("dispersion"),
      py::arg("striker_velocity"));
  m.def(
      "_study",
      [](const std::filesystem::path& scene, const std::filesystem::path& output,
         const std::string& sweep, const py::object& refine, const py::object& tolerance,
         const std::optional<std::string>& contact, const std::optional<std::string>& stepping,
         const py::object& courant, const py::object& threads,
         const std::optional<std::filesystem::path>& distributions, const py::object& draws,
         const py::object& seed) {
        StudyArgs a;
        a.scene = scene;
        a.output = output;
        if (distributions) a.distributions = *distributions;
        a.draws = optional_number<std::size_t>(draws, "draws");
        a.seed = optional_number<std::uint64_t>(seed, "seed");
        const auto s = enum_value(kSweepNames, sweep);
        if (!s)
          throw input_error("sweep", "", "\"" + sweep + "\"",
                            "expected pareto, stability or monte-carlo");
        a.sweep = *s;
        a.refine = number<int>(refine, "refine");
        a.overrides = overrides_of(tolerance, contact, stepping, courant, threads);
        return run_released([&] { return run_study(a); });
      },
      py::arg("scene"), py::arg("output"), py::arg("sweep"), py::arg("refine"),
      py::arg("tolerance"), py::arg("contact"), py::arg("stepping"), py::arg("courant"),
      py::arg("threads"), py::arg("distributions"), py::arg("draws"), py::arg("seed"));
  m.def(
      "_fit",
      [](const std::filesystem::path& campaign, const std::filesystem::path& output,
         const py::object& threads, const py::object& max_iterations,
         const py::object& relative_step, const py::object& bootstrap, const py::object& seed) {
        FitArgs a;
        a.campaign = campaign;
        a.output = output;
        a.options.threads = number<int>(threads, "threads");
        a.options.max_iterations = number<int>(max_iterations, "max_iterations");
        a.options.relative_step = number<double>(relative_step, "relative_step");
        a.options.bootstrap = number<int>(bootstrap, "bootstrap");
        a.options.seed = number<unsigned long>(seed, "seed");
        a.quiet = true;
        return run_released([&] { return run_fit(a); });
      },
      py::arg("campaign"), py::arg("output"), py::arg("threads"), py::arg("max_iterations"),
      py::arg("relative_step"), py::arg("bootstrap"), py::arg("seed"));
  m.def(
      "_dispersion",
      [](const py::object& poisson, const py::list& a_over_lambda,
         const py::object& max_a_over_lambda, const py::object& points, const py::object& radius_m,
         const py::object& c0_m_s, const std::filesystem::path& output) {
        std::vector<double> ratios;
        for (std::size_t i = 0; i < a_over_lambda.size(); ++i)
          ratios.push_back(
              number<double>(a_over_lambda[i], "a_over_lambda[" + std::to_string(i) + "]"));
        DispersionArgs a{number<double>(poisson, "poisson"),
                         ratios,
                         number<double>(max_a_over_lambda, "max_a_over_lambda"),
                         number<int>(points, "points"),
                         optional_number<double>(radius_m, "radius_m"),
                         optional_number<double>(c0_m_s, "c0_m_s"),
                         output};
        return run_released([&] { return run_dispersion(a); });
      },
      py::arg("poisson"), py::arg("a_over_lambda"), py::arg("max_a_over_lambda"), py::arg("points"),
      py::arg("radius_m"), py::arg("c0_m_s"), py::arg("output"));
  // The files a run of compare, study or fit read, as the command declares them to its output
  // folder: result.save(dir) refuses a dir that is or holds one, as the command does (a study of
  // a plan's scene.json saved over the plan deleted the scene).
  m.def(
      "_inputs",
      [](const std::string& command, const std::filesystem::path& file,
         const std::filesystem::path& distributions) {
        return run_released([&] {
          if (command == "fit") return fit_inputs(prepare_fit(file, FitOptions{}));
          const Scene scene = read_scene(file);
          return command == "study" ? study_inputs(scene, distributions) : scene_inputs(scene);
        });
      },
      py::arg("command"), py::arg("file"), py::arg("distributions"));
  // result.save(dir) of those: the command's folder copied with the output folder's own rules
  // (checks, marker, atomic replacement; core/output_folder.hpp).
  m.def(
      "_save_folder",
      [](const std::filesystem::path& from, const std::filesystem::path& dir,
         const std::string& command, const std::vector<std::filesystem::path>& inputs) {
        run_released([&] {
          OutputFolder out(dir, command, inputs);
          for (const auto& e : std::filesystem::directory_iterator(from))
            if (e.path().filename() != kOutputMarker)
              std::filesystem::copy(e.path(), out.file(e.path().filename().string()),
                                    std::filesystem::copy_options::recursive);
          out.commit();
          return 0;
        });
      },
      py::arg("from"), py::arg("dir"), py::arg("command"), py::arg("inputs"));
}
