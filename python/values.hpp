// Python values taken in: numbers, text for messages, dicts as JSON, the run options shared by the
// commands, and the range checks of an edited scene value.
#pragma once

#include <pybind11/pybind11.h>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "model/run_overrides.hpp"

namespace shpb::python {

namespace py = pybind11;

// Python text as UTF-8 for a message: a lone surrogate (a file name that is not UTF-8, as
// os.fsdecode gives it) as its \udcff escape instead of a failed conversion.
std::string message_text(const py::handle& s);

// An object as a message shows it: its repr on one line (a DataFrame's repr has many: its type).
std::string shown(const py::handle& o);

// Some text per edited field: name=value, SI units in the names (the attributes' own names).
std::string fields(std::initializer_list<std::pair<const char*, double>> values);

// The JSON value of an object json.dumps cannot write itself: a numpy scalar or 0-d array of a
// number, bool or text (its value; a float16 or long double as the nearest double), a path (its
// text). nullopt for anything else: complex numbers, dates, arrays of several values (a numpy
// array is no JSON list: `.tolist()` makes it one), masked values, bytes, ...
std::optional<py::object> json_value_of(const py::handle& o);

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
// A path handed to the module (a str or an os.PathLike, as open() takes it); anything else a
// TypeError naming `name`, what was given and what is expected, in one line (pybind11's own names
// every overload on several lines).
std::filesystem::path path_value(const py::handle& o, const std::string& name);
// Text (a str); anything else a TypeError naming `name` and `expected`.
std::string text_value(const py::handle& o, const std::string& name, const std::string& expected);
inline std::optional<std::string> optional_text(const py::handle& o, const std::string& name,
                                                const std::string& expected) {
  if (o.is_none()) return std::nullopt;
  return text_value(o, name, expected);
}

// True or False (a numpy bool by its value), as a file's JSON boolean; anything else a TypeError
// naming `name`.
bool boolean(const py::handle& o, const std::string& name);

template <class T>
std::optional<T> optional_number(const py::handle& o, const std::string& name) {
  if (o.is_none()) return std::nullopt;
  return number<T>(o, name);
}

// Python strings, ints and floats, nested in dicts and lists, as JSON text (json.dumps; numpy
// scalars by their value). NaN and infinity are not JSON: refused as the scene file would be, in
// the reader's one line naming `file`, the JSON path and the value.
std::string dict_to_json_text(const py::object& d, const std::filesystem::path& file);

// A tolerance (a gauge error) as a fraction: text with its unit ("1 %") or a number; None: none.
std::optional<double> tolerance_value(const py::object& t);

// The keyword arguments tolerance, contact, stepping, courant and threads of a run (the commands'
// options of those names) as the library's overrides, progress output off.
RunOverrides overrides_of(const py::object& tolerance, const py::object& contact,
                          const py::object& stepping, const py::object& courant,
                          const py::object& threads);

// An edited number meets the range the scene reader gives its JSON key (model/scene_reader.cpp,
// model/material_reader.cpp), so that a run never starts from a value no scene file could hold.
enum class Range { kFinite, kPositive, kNonNegative, kFraction };

inline double checked_value(const py::object& value, const char* name, Range range) {
  const double x = number<double>(value, name);
  const bool ok =
      std::isfinite(x) &&
      (range == Range::kFinite || (range == Range::kPositive && x > 0) ||
       (range == Range::kNonNegative && x >= 0) || (range == Range::kFraction && x >= 0 && x <= 1));
  if (!ok)
    throw input_error("scene edit", name, format_double(x),
                      range == Range::kPositive      ? "must be > 0"
                      : range == Range::kNonNegative ? "must be >= 0"
                      : range == Range::kFraction    ? "must be in [0, 1]"
                                                     : "must be a finite number");
  return x;
}

template <class T>
auto checked(double T::*field, const char* name, Range range) {
  return [field, name, range](T& object, const py::object& value) {
    object.*field = checked_value(value, name, range);
  };
}

}  // namespace shpb::python
