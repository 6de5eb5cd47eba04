// simulate: _simulate, the library's simulate on a scene in memory, and its result _Simulation
// (the tables as numpy views, summary.json's values, save as `shpb simulate` writes its folder).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "core/output_folder.hpp"
#include "interrupt.hpp"
#include "model/scene_inputs.hpp"
#include "solver/simulation.hpp"
#include "values.hpp"
#include "views.hpp"

namespace shpb::python {

namespace {

struct Simulation {
  Scene scene;  // as run: overrides applied, meshes chosen
  SimulationResult result;
};

}  // namespace

void bind_simulate(py::module_& m) {
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
      [](const Scene& scene, const py::object& tolerance, const py::object& contact,
         const py::object& stepping, const py::object& courant, const py::object& threads,
         const py::object& full_model) {
        auto s = std::make_shared<Simulation>();
        s->scene = scene;
        const RunOverrides overrides = overrides_of(tolerance, contact, stepping, courant, threads);
        SimulationOptions options;
        options.full_model = boolean(full_model, "full_model");
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
      py::arg("threads") = py::int_(0), py::arg("full_model") = py::bool_(false));
}

}  // namespace shpb::python
