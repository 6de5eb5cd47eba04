// Python values taken in (python/values.hpp).
#include "values.hpp"

#include <pybind11/stl/filesystem.h>

#include "app/cli_options.hpp"
#include "core/json_document.hpp"
#include "core/json_value.hpp"
#include "core/units.hpp"
#include "model/scene.hpp"

namespace shpb::python {

std::string message_text(const py::handle& s) {
  return py::bytes(py::str(s).attr("encode")("utf-8", "backslashreplace")).cast<std::string>();
}

std::string shown(const py::handle& o) {
  const std::string r = message_text(py::repr(o));
  if (r.find('\n') == std::string::npos) return r;
  return "a " + message_text(py::type::of(o).attr("__name__"));
}

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

std::filesystem::path path_value(const py::handle& o, const std::string& name) {
  try {
    return o.cast<std::filesystem::path>();  // a str, bytes or os.PathLike, as pybind11 takes it
  } catch (const py::cast_error&) {
    throw py::type_error(name + ": " + shown(o) + ": expected a path (a str or os.PathLike)");
  }
}

std::string text_value(const py::handle& o, const std::string& name, const std::string& expected) {
  if (!py::isinstance<py::str>(o))
    throw py::type_error(name + ": " + shown(o) + ": expected " + expected);
  return o.cast<std::string>();
}

namespace {

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

}  // namespace

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

bool boolean(const py::handle& o, const std::string& name) {
  py::object v = py::reinterpret_borrow<py::object>(o);
  if (const auto j = json_value_of(o)) v = *j;
  if (!py::isinstance<py::bool_>(v))
    throw py::type_error(name + ": " + shown(o) + ": expected True or False");
  return v.cast<bool>();
}

std::string fields(std::initializer_list<std::pair<const char*, double>> values) {
  std::string text;
  for (const auto& [name, value] : values)
    text += (text.empty() ? "" : ", ") + std::string(name) + "=" + format_double(value);
  return text;
}

RunOverrides overrides_of(const py::object& tolerance, const py::object& contact,
                          const py::object& stepping, const py::object& courant,
                          const py::object& threads) {
  // Text as the command line gives it, read by the command's own function (one check, one
  // message: courant="0.9" is --courant 0.9, a TypeError before); a number as a number.
  RunOverrides o;
  RunOptionText text;
  text.contact = optional_text(contact, "contact", "the name of a contact method").value_or("");
  text.stepping =
      optional_text(stepping, "stepping", "\"asynchronous\" or \"global\"").value_or("");
  if (py::isinstance<py::str>(tolerance))
    text.tolerance = message_text(tolerance);
  else
    o.tolerance = tolerance_value(tolerance);
  if (py::isinstance<py::str>(courant))
    text.courant = message_text(courant);
  else
    o.courant = optional_number<double>(courant, "courant");
  resolve_run_options(o, text);
  o.threads = number<int>(threads, "threads");
  o.quiet = true;
  o.warnings_on_stderr = false;  // returned: result.warnings (python/shpb/__init__.py)
  return o;
}

}  // namespace shpb::python
