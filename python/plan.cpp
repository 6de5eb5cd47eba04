// plan: the command's search (app/plan.cpp: prepare_plan, search_plan) run once, its result held
// in memory and written by the command's writer wherever it is saved: the planned scene.json
// names its material files relative to the folder it is written in.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <string>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "bindings.hpp"
#include "core/output_folder.hpp"
#include "interrupt.hpp"
#include "values.hpp"

namespace shpb::python {

namespace {

// A quantity option as the command reads its text ("2500 1/s"), or a number in SI units.
double quantity_value(const py::object& value, const std::string& option, const char* name,
                      Dimension d) {
  if (py::isinstance<py::str>(value)) return quantity_option(option, message_text(value), d);
  return number<double>(value, name);
}

// A gauge-error option as the command reads its text ("3 %"), or a fraction; its range is
// checked by PlanOptions::IsValid, the command's check.
double tolerance_of(const py::object& value, const std::string& option, const char* name) {
  if (py::isinstance<py::str>(value)) return tolerance_option(option, message_text(value));
  return number<double>(value, name, "expected a gauge error such as \"1 %\" or 0.01");
}

}  // namespace

void bind_plan(py::module_& m) {
  py::class_<PlannedTest, std::shared_ptr<PlannedTest>>(m, "_PlannedTest")
      .def_property_readonly("inputs", [](const PlannedTest& p) { return plan_inputs(p.input); })
      .def(
          "save",
          [](const PlannedTest& p, const std::filesystem::path& dir) {
            run_released([&] {
              OutputFolder out(dir, "plan", plan_inputs(p.input));
              write_plan(p, out);
              return 0;
            });
          },
          py::arg("dir"));
  m.def(
      "_plan",
      [](const std::filesystem::path& scene, const std::filesystem::path& shown,
         const py::object& rate, const py::object& strain, const py::object& search_tolerance,
         const py::object& tolerance, const py::object& threads) {
        // The options in the command's order: its text read, then its checks (prepare_plan).
        PlanArgs a;
        a.scene = scene;
        a.targets.rate_1_s = quantity_value(rate, "--rate", "rate", Dimension::kStrainRate);
        a.targets.strain = quantity_value(strain, "--strain", "strain", Dimension::kDimensionless);
        a.options.search_tolerance =
            tolerance_of(search_tolerance, "--search-tolerance", "search_tolerance");
        a.options.verify_tolerance = tolerance_of(tolerance, "--tolerance", "tolerance");
        a.options.threads = number<int>(threads, "threads");
        a.quiet = true;
        return run_released([&] {
          auto p = std::make_shared<PlannedTest>(prepare_plan(a));
          p->file =
              shown;  // a Scene's temporary file named as the user knows it (shpb/__init__.py)
          search_plan(*p);
          return p;
        });
      },
      py::arg("scene"), py::arg("shown"), py::arg("rate"), py::arg("strain"),
      py::arg("search_tolerance"), py::arg("tolerance"), py::arg("threads"));
}

}  // namespace shpb::python
