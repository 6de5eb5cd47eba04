// process: _process, the library's process_scene on a scene in memory (with its Monte Carlo
// uncertainty), and its result _Processing (signals, pulses and curve as numpy views,
// summary.json's values, save as `shpb process` writes its folder).
#include "app/process.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "analysis/process_outputs.hpp"
#include "analysis/uncertainty.hpp"
#include "bindings.hpp"
#include "core/error.hpp"
#include "core/options_check.hpp"
#include "interrupt.hpp"
#include "output_schema.hpp"
#include "values.hpp"
#include "views.hpp"

namespace shpb::python {

namespace {

struct Processing {
  Scene scene;
  ProcessOutcome outcome;
};

// A scene without a specimen: the command's bars-together check.
struct BarChecking {
  Scene scene;
  BarCheckOutcome outcome;
};

void bind_bar_check(py::module_& m) {
  py::class_<BarChecking, std::shared_ptr<BarChecking>>(m, "_BarCheck")
      .def_property_readonly("scene", [](const BarChecking& b) { return b.scene; })
      .def_property_readonly("pulses",
                             [](py::object self) {
                               // pulses.csv's columns, in its order (docs/outputs.md).
                               namespace k = schema::bar_check_pulses;
                               const BarCheckResult& r = self.cast<BarChecking&>().outcome.result;
                               py::dict d;
                               d[k::time_s] = view(r.time_s, self);
                               d[k::far_measured] = view(r.far_measured, self);
                               d[k::far_pochhammer_chree] = view(r.far_dispersion, self);
                               d[k::far_time_shift] = view(r.far_time_shift, self);
                               return d;
                             })
      .def_property_readonly(
          "summary",
          [](const BarChecking& b) {
            return json_to_python(bar_check_summary(b.outcome, b.scene, b.scene.file.string()));
          })
      .def_property_readonly("warnings", [](const BarChecking& b) { return b.outcome.warnings; })
      .def(
          "save",
          [](const BarChecking& b, const std::filesystem::path& dir) {
            run_released([&] {
              write_bar_check(b.outcome, b.scene, b.scene.file.string(), dir);
              return 0;
            });
          },
          py::arg("dir"));
}

// `text` with every `file` in it named `shown`.
std::string renamed(std::string text, const std::string& file, const std::string& shown) {
  for (auto at = text.find(file); at != std::string::npos; at = text.find(file, at + shown.size()))
    text.replace(at, file.size(), shown);
  return text;
}

// The reduction of signals read from `signals`; a SimulationResult's, written to a temporary
// gauges.csv (shpb/__init__.py), is named `shown` wherever the file would be named: summary.json,
// the warnings and an error's line (the temporary is gone when the call returns).
ProcessOutcome process_signals(const Scene& scene,
                               const std::optional<std::filesystem::path>& signals,
                               const std::optional<std::string>& shown,
                               const MonteCarloOptions& monte_carlo) {
  const std::string file = signals ? signals->string() : "";
  try {
    ProcessOutcome o = run_released([&] {
      ProcessOutcome o = process_scene(scene, signals, false);
      add_uncertainty(scene, monte_carlo, o);
      return o;
    });
    if (shown) {
      o.signals_shown = *shown;
      for (auto& w : o.warnings) w = renamed(w, file, *shown);
    }
    return o;
  } catch (const InputError& e) {
    if (!shown) throw;
    throw InputError(renamed(e.what(), file, *shown));
  } catch (const NumericalError& e) {
    if (!shown) throw;
    throw NumericalError(renamed(e.what(), file, *shown));
  }
}

}  // namespace

void bind_process(py::module_& m) {
  bind_bar_check(m);
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
         const py::object& draws, const py::object& seed, const py::object& threads,
         const std::optional<std::string>& signals_shown) -> py::object {
        MonteCarloOptions monte_carlo;
        monte_carlo.draws = number<std::size_t>(draws, "draws");
        monte_carlo.seed = number<std::uint64_t>(seed, "seed");
        monte_carlo.threads = number<int>(threads, "threads");
        require_valid(monte_carlo);  // before the scene's own errors, as the command checks it
        if (!scene.specimen) {       // the bars pushed together: the command's check (process_into)
          auto b = std::make_shared<BarChecking>();
          b->scene = scene;
          b->outcome =
              run_released([&] { return check_scene_bars(scene, signals.has_value(), false); });
          return py::cast(b);
        }
        auto p = std::make_shared<Processing>();
        p->scene = scene;
        p->outcome = process_signals(p->scene, signals, signals_shown, monte_carlo);
        if (!p->outcome.failure.empty()) throw NumericalError(p->outcome.failure);
        return py::cast(p);
      },
      py::arg("scene"), py::arg("signals") = py::none(), py::arg("draws") = py::int_(kDefaultDraws),
      py::arg("seed") = py::int_(kDefaultSeed), py::arg("threads") = py::int_(0),
      py::arg("signals_shown") = py::none());
}

}  // namespace shpb::python
