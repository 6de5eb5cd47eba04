// Library results handed to Python: numpy views of time series, summaries as Python objects.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "core/time_series.hpp"

namespace shpb::python {

namespace py = pybind11;

// A read-only numpy array over a vector that `owner` (a Python object holding it) keeps alive:
// no copy of the library's time series.
py::array_t<double> view(const std::vector<double>& v, py::handle owner);

// Columns of a TimeSeries as {"time_s": ..., name: ...}, in the CSV's order.
py::dict series(const TimeSeries& s, py::handle owner);

// summary.json's values as Python objects, keys in the file's order (what json.loads of the
// file gives, without writing and parsing the text).
py::object json_to_python(const nlohmann::ordered_json& j);

}  // namespace shpb::python
