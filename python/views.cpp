// Library results handed to Python (python/views.hpp).
#include "views.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace shpb::python {

py::array_t<double> view(const std::vector<double>& v, py::handle owner) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()), v.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::dict series(const TimeSeries& s, py::handle owner) {
  py::dict d;
  d["time_s"] = view(s.time_s, owner);
  for (std::size_t c = 0; c < s.columns.size(); ++c)
    d[s.columns[c].c_str()] = view(s.values[c], owner);
  return d;
}

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

}  // namespace shpb::python
