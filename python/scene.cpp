// The scene and its parts: Scene (load, from_dict, its bars, the run settings a scene holds) and
// Bar.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "analysis/monte_carlo.hpp"  // set_bar_diameter
#include "bindings.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "interrupt.hpp"
#include "model/input_limits.hpp"
#include "model/scene_validation.hpp"
#include "model/scene_writer.hpp"
#include "model/test_setup.hpp"
#include "model/wave_travel.hpp"
#include "values.hpp"

namespace shpb::python {

namespace {

// A bar of a scene, as Python holds it: the scene and the bar's index (an edit of its length
// places the scene's gauges given by their distance to the specimen again, which needs the scene).
struct BarView {
  py::object scene;
  std::size_t index = 0;
  Scene& owner() const { return scene.cast<Scene&>(); }
  BarSpec& bar() const { return owner().bars[index]; }
};

// The index of the bar named `name` or at index `i` (negative from the end, as Python lists).
std::size_t bar_index(const Scene& s, const py::object& key) {
  if (py::isinstance<py::str>(key)) {
    const std::string name = message_text(key);  // a lone surrogate names no bar
    for (std::size_t i = 0; i < s.bars.size(); ++i)
      if (s.bars[i].name == name) return i;
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
  return static_cast<std::size_t>(i);
}

// A bar's length edit: its range, then its gauges on it, as the scene reader places them: one given
// by its position stays there (and must lie on the bar), one given by its distance to the specimen
// keeps that distance (its place on its bar moves, and every gauge beyond this bar too).
void set_length(const BarView& v, const py::object& value) {
  Scene edited = v.owner();
  BarSpec& b = edited.bars[v.index];
  checked(&BarSpec::length_m, "bar.length_m", Range::kPositive)(b, value);
  const double x = b.length_m;
  for (std::size_t i = 0; i < edited.bars.size(); ++i)
    for (auto& g : edited.bars[i].gauges) {
      if (g.distance_to_specimen_m) {
        const GaugePlacement place = place_gauge_at_distance(edited, i, *g.distance_to_specimen_m);
        if (!place.problem.empty())
          throw input_error("scene edit", "bar.length_m", format_double(x),
                            "gauge \"" + g.name + "\" at distance_to_specimen " +
                                format_double(*g.distance_to_specimen_m) + " m " + place.problem);
        g.position_m = place.position_m;
      } else if (i == v.index) {
        if (const std::string what = gauge_position_problem(g.position_m, x); !what.empty())
          throw input_error(
              "scene edit", "bar.length_m", format_double(x),
              "gauge \"" + g.name + "\" at " + format_double(g.position_m) + " m " + what);
      }
    }
  // Field by field: a Material taken from a bar views the scene's own bars, which stay in place.
  Scene& s = v.owner();
  s.bars[v.index].length_m = x;
  for (std::size_t i = 0; i < s.bars.size(); ++i)
    for (std::size_t k = 0; k < s.bars[i].gauges.size(); ++k)
      s.bars[i].gauges[k].position_m = edited.bars[i].gauges[k].position_m;
}

// A setter of a bar's field through its view.
template <class Set>
auto on_bar(Set set) {
  return [set](const BarView& v, const py::object& value) { set(v.bar(), value); };
}

void bind_bar(py::module_& m) {
  py::class_<BarView>(m, "Bar")
      .def_property_readonly("name", [](const BarView& v) { return v.bar().name; })
      .def_property_readonly("material",
                             [](py::object self) {
                               return py::cast(&self.cast<BarView&>().bar().material,
                                               py::return_value_policy::reference_internal, self);
                             })
      .def_property(
          "length_m", [](const BarView& v) { return v.bar().length_m; }, &set_length)
      .def_property_readonly("area_m2", [](const BarView& v) { return v.bar().area_m2; })
      .def_property(
          "diameter_m", [](const BarView& v) { return v.bar().diameter_m; },
          // The section scales with it (a bar given its area keeps its shape: the equivalent
          // circular diameter), as a Monte Carlo draw of a diameter does.
          [](const BarView& v, const py::object& value) {
            set_bar_diameter(v.bar(), checked_value(value, "bar.diameter_m", Range::kPositive));
          })
      .def_property(
          "velocity_m_s", [](const BarView& v) { return v.bar().velocity_m_s; },
          on_bar(checked(&BarSpec::velocity_m_s, "bar.velocity_m_s", Range::kFinite)))
      .def_property(
          "elements", [](const BarView& v) { return v.bar().elements; },
          on_bar([](BarSpec& b, const py::object& value) {
            const int n = number<int>(value, "bar.elements");
            if (n < 0 || n > kMaxElements)
              throw input_error("scene edit", "bar.elements", std::to_string(n),
                                "must be in [1, " + std::to_string(kMaxElements) +
                                    "], or 0 for the automatic mesh");
            b.elements = n;
          }))
      .def_property(
          "gap_m", [](const BarView& v) { return v.bar().gap_m; },
          [](const BarView& v, const py::object& value) {
            BarSpec edited = v.bar();
            checked(&BarSpec::gap_m, "bar.gap_m", Range::kNonNegative)(edited, value);
            // The last bar's gap (0) was kept and never used.
            if (edited.gap_m > 0 && v.index + 1 == v.owner().bars.size())
              throw input_error("scene edit", "bar.gap_m", format_double(edited.gap_m),
                                kLastBarGap);
            v.bar().gap_m = edited.gap_m;
          })
      .def_property(
          "inertia", [](const BarView& v) { return v.bar().inertia; },
          [](const BarView& v, const py::object& value) {
            // True or False (a numpy bool by its value), as the file's JSON boolean.
            Scene edited = v.owner();
            edited.bars[v.index].inertia = boolean(value, "bar.inertia");
            if (const std::string what = radial_inertia_problem(edited, v.index); !what.empty())
              throw input_error("scene edit", "bar.inertia", "True", what);
            v.bar().inertia = edited.bars[v.index].inertia;
          })
      .def_property_readonly("gauges",
                             [](const BarView& v) {
                               py::dict d;
                               for (const auto& g : v.bar().gauges)
                                 d[g.name.c_str()] = g.position_m;
                               return d;
                             })
      .def("__repr__", [](const BarView& v) {
        const BarSpec& b = v.bar();
        return "<shpb.Bar " + b.name + ": " + b.material.name + ", " + format_double(b.length_m) +
               " m, " + format_double(b.velocity_m_s) + " m/s>";
      });
}

}  // namespace

void bind_scene(py::module_& m) {
  bind_bar(m);
  // Edits (e.g. scene.striker.velocity_m_s = 12) act on the scene in memory; a run checks the
  // edited scene with the one validation every command applies (model/scene_validation.hpp).
  // The scene's file made absolute when read: its relative paths (measurement data, read when the
  // scene is processed) then resolve as they did when it was loaded, whatever os.chdir (a
  // notebook's %cd) did in between.
  py::class_<Scene>(m, "Scene")
      .def_static(
          "load",
          [](const py::object& given) {
            const std::filesystem::path file = path_value(given, "Scene.load: path");
            // An empty path (std::filesystem::absolute throws on it) is the reader's to refuse.
            return read_scene(file.empty() ? file : std::filesystem::absolute(file));
          },
          py::arg("path"))
      .def_static(
          "from_dict",
          [](const py::object& d, const py::object& given) {
            const std::filesystem::path file = path_value(given, "Scene.from_dict: file");
            if (file.empty())
              throw input_error("file", "", "\"\"",
                                "expected the path the dict's relative paths are written from, "
                                "such as \"scene.json\"");
            const std::filesystem::path anchored = std::filesystem::absolute(file);
            return read_scene_text(dict_to_json_text(d, anchored), anchored);
          },
          py::arg("d"), py::arg("file") = py::str("scene.json"))
      .def(
          "save",
          [](const Scene& s, const py::object& path, const py::object& overwrite) {
            const std::filesystem::path file = path_value(path, "Scene.save: path");
            const bool replace = boolean(overwrite, "Scene.save: overwrite");
            const Scene scene = s;  // copied with the GIL held: another thread may edit it
            run_released([&] {
              save_scene(scene, file, replace);
              return 0;
            });
          },
          py::arg("path"), py::arg("overwrite") = false)
      .def("to_dict",
           [](const Scene& s) {
             // The file save(scene.file) would write, as a dict (json.loads of its text).
             return py::module_::import("json").attr("loads")(scene_file_text(s, s.file));
           })
      .def_readwrite("name", &Scene::name)
      .def_property_readonly("file", [](const Scene& s) { return s.file; })
      .def_property_readonly("bars",
                             [](py::object self) {
                               py::list l;
                               for (std::size_t i = 0; i < self.cast<Scene&>().bars.size(); ++i)
                                 l.append(BarView{self, i});
                               return l;
                             })
      .def(
          "bar",
          [](py::object self, const py::object& key) {
            return BarView{self, bar_index(self.cast<Scene&>(), key)};
          },
          py::arg("key"))
      .def_property_readonly("specimen",
                             [](py::object self) -> py::object {
                               const Scene& s = self.cast<Scene&>();
                               if (!s.specimen) return py::none();
                               return py::cast(BarView{self, *s.specimen});
                             })
      .def_property_readonly("striker",
                             [](py::object self) -> py::object {
                               const auto i = striker_bar(self.cast<Scene&>());
                               if (!i) return py::none();
                               return py::cast(BarView{self, *i});
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
            apply_overrides(
                overrides_of(tolerance, py::none(), py::none(), py::none(), py::int_(0)), copy);
          },
          py::arg("tolerance") = py::none())
      .def("copy", [](const Scene& s) { return Scene(s); })
      .def("__copy__", [](const Scene& s) { return Scene(s); })
      .def("__deepcopy__", [](const Scene& s, py::object) { return Scene(s); })
      .def("__repr__", [](const Scene& s) {
        return "<shpb.Scene " + s.name + ": " + std::to_string(s.bars.size()) + " bars>";
      });
}

}  // namespace shpb::python
