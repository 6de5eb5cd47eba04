// The other commands: compare, study, fit, calibrate, dispersion and process of a campaign run
// by the command's own function, and
// the files a result's save(dir) declares and copies (python/shpb/__init__.py wraps them).
#include "app/commands.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/process_campaign.hpp"
#include "app/cli_options.hpp"
#include "bindings.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "core/shards.hpp"
#include "interrupt.hpp"
#include "values.hpp"

namespace shpb::python {

namespace {

// `shpb process` of several tests: a campaign file or the scenes' files.
CampaignOptions campaign_options(const std::optional<std::filesystem::path>& campaign,
                                 const std::vector<std::filesystem::path>& scenes) {
  CampaignOptions c;
  c.campaign = campaign;
  c.scenes = scenes;
  return c;
}

// process of a campaign: the command's process_campaign, its folder read back in Python.
void bind_process_campaign(py::module_& m) {
  m.def(
      "_process_campaign",
      [](const std::optional<std::filesystem::path>& campaign,
         const std::vector<std::filesystem::path>& scenes, const std::filesystem::path& output,
         const py::list& flow_stress_at, const py::object& draws, const py::object& seed,
         const py::object& threads, const py::object& shard, const py::object& merge) {
        CampaignOptions c = campaign_options(campaign, scenes);
        c.shard = optional_text(shard, "shard", "\"K/N\", e.g. \"1/4\"").value_or("");  // --shard
        c.merge = boolean(merge, "merge");                                              // --merge
        for (std::size_t i = 0; i < flow_stress_at.size(); ++i)  // --flow-stress-at
          c.flow_strains.push_back(
              number<double>(flow_stress_at[i], "flow_stress_at[" + std::to_string(i) + "]"));
        c.output = output;
        c.draws = optional_number<std::size_t>(draws, "draws");  // None: not given
        c.seed = optional_number<std::uint64_t>(seed, "seed");
        c.threads = number<int>(threads, "threads");
        c.print_warnings = false;  // result.warnings, from each test's summary.json
        // Its checks first (CampaignOptions::IsValid), as the command's; the folder written.
        return run_released([&] { return process_campaign(c); });
      },
      py::arg("campaign"), py::arg("scenes"), py::arg("output"), py::arg("flow_stress_at"),
      py::arg("draws"), py::arg("seed"), py::arg("threads"), py::arg("shard"), py::arg("merge"));
}

// study, and its steps (--plan DIR, --run DIR --shard K/N, --merge DIR): what the step wrote, the
// plan's folder, the shard's part file or the study's folder.
void bind_study(py::module_& m) {
  m.def(
      "_study",
      [](const std::filesystem::path& scene, const std::filesystem::path& output,
         const py::object& sweep_name, const py::object& refine, const py::object& tolerance,
         const py::object& contact, const py::object& stepping, const py::object& courant,
         const py::object& threads, const std::optional<std::filesystem::path>& distributions,
         const py::object& draws, const py::object& seed,
         const std::optional<std::filesystem::path>& plan,
         const std::optional<std::filesystem::path>& run, const py::object& shard,
         const std::optional<std::filesystem::path>& merge) {
        StudyArgs a;
        a.scene = scene;
        a.output = output;
        if (distributions) a.distributions = *distributions;
        a.draws = optional_number<std::size_t>(draws, "draws");
        a.seed = optional_number<std::uint64_t>(seed, "seed");
        if (const auto sweep = optional_text(sweep_name, "sweep", "the name of a sweep")) {
          check_choice("--sweep", *sweep, enum_names(kSweepNames));  // the command's check
          a.sweep = *enum_value(kSweepNames, *sweep);
        }
        a.refine = number<int>(refine, "refine");
        a.overrides = overrides_of(tolerance, contact, stepping, courant, threads);
        a.plan = plan;
        a.run = run;
        a.shard = optional_text(shard, "shard", "\"K/N\", e.g. \"1/4\"").value_or("");
        a.merge = merge;
        const int code = run_released([&] { return run_study(a); });
        const std::filesystem::path wrote =
            plan    ? *plan
            : run   ? *run / "parts" / (part_name(parse_shard("--shard", a.shard)) + ".json")
            : merge ? (output.empty() ? *merge / "result" : output)
                    : output;
        return std::pair(code, wrote);
      },
      py::arg("scene"), py::arg("output"), py::arg("sweep"), py::arg("refine"),
      py::arg("tolerance"), py::arg("contact"), py::arg("stepping"), py::arg("courant"),
      py::arg("threads"), py::arg("distributions"), py::arg("draws"), py::arg("seed"),
      py::arg("plan"), py::arg("run"), py::arg("shard"), py::arg("merge"));
}

void bind_command_runs(py::module_& m) {
  // validate: what `shpb validate --json` prints of the scene, as a dict.
  m.def(
      "_validate",
      [](const Scene& scene, const py::object& tolerance, const py::object& contact,
         const py::object& stepping, const py::object& courant, const py::object& threads) {
        const RunOverrides o = overrides_of(tolerance, contact, stepping, courant, threads);
        Scene copy = scene;  // with the GIL held: another thread may edit it
        const std::string text = run_released([&] { return validate_setup(std::move(copy), o); });
        return py::module_::import("json").attr("loads")(text);
      },
      py::arg("scene"), py::arg("tolerance"), py::arg("contact"), py::arg("stepping"),
      py::arg("courant"), py::arg("threads"));
  // compare, fit, calibrate and dispersion: the command's own function, writing its folder (or
  // file) where the Python side reads it back (python/shpb/__init__.py). The exit code is
  // returned: 3 is a result written with a numerical failure said in its summary.
  m.def(
      "_compare",
      [](const std::filesystem::path& scene, const std::filesystem::path& output,
         const py::object& tolerance, const py::object& contact, const py::object& stepping,
         const py::object& courant, const py::object& threads, const py::object& dispersion,
         const py::object& striker_velocity) {
        // A velocity as the option takes it ("15 m/s", a bare number in m/s), or a number.
        const std::optional<double> velocity =
            py::isinstance<py::str>(striker_velocity)
                ? std::optional(quantity_option(
                      "--striker-velocity", message_text(striker_velocity), Dimension::kVelocity))
                : optional_number<double>(striker_velocity, "striker_velocity");
        CompareArgs a{scene, output, overrides_of(tolerance, contact, stepping, courant, threads),
                      boolean(dispersion, "dispersion"), velocity};
        return run_released([&] { return run_compare(a); });
      },
      py::arg("scene"), py::arg("output"), py::arg("tolerance"), py::arg("contact"),
      py::arg("stepping"), py::arg("courant"), py::arg("threads"), py::arg("dispersion"),
      py::arg("striker_velocity"));
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
      "_calibrate",
      [](const std::vector<std::filesystem::path>& scenes, const std::filesystem::path& output,
         const py::object& threads) {
        CalibrateArgs a;
        a.scenes = scenes;
        a.output = output;
        a.threads = number<int>(threads, "threads");
        a.quiet = true;
        a.warnings_on_stderr = false;  // result.warnings (python/shpb/__init__.py)
        return run_released([&] { return run_calibrate(a); });
      },
      py::arg("scenes"), py::arg("output"), py::arg("threads"));
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
                         optional_number<double>(max_a_over_lambda, "max_a_over_lambda"),
                         optional_number<int>(points, "points"),
                         optional_number<double>(radius_m, "radius_m"),
                         optional_number<double>(c0_m_s, "c0_m_s"),
                         output};
        return run_released([&] { return run_dispersion(a); });
      },
      py::arg("poisson"), py::arg("a_over_lambda"), py::arg("max_a_over_lambda"), py::arg("points"),
      py::arg("radius_m"), py::arg("c0_m_s"), py::arg("output"));
  // report: the command's run of the report script; its warnings returned, its error raised.
  m.def(
      "_report",
      [](const std::filesystem::path& folder) {
        std::vector<std::string> warnings;
        const int code = run_released([&] { return run_report(ReportArgs{folder, &warnings}); });
        if (code != 0)  // killed (the out-of-memory killer): the command's exit 3
          throw WriteError(folder.string() + ": the report script stopped (exit " +
                           std::to_string(code) + "): the report was not finished");
        return warnings;
      },
      py::arg("folder"));
}

}  // namespace

void bind_commands(py::module_& m) {
  bind_command_runs(m);
  bind_study(m);
  bind_process_campaign(m);
  // The files a run of compare, study, fit or calibrate read (`files`: the one scene or campaign,
  // calibrate's scenes), as the command declares them to its output folder: result.save(dir)
  // refuses a dir that is or holds one, as the command does (a study of a plan's scene.json saved
  // over the plan deleted the scene).
  m.def(
      "_inputs",
      [](const std::string& command, const std::vector<std::filesystem::path>& files,
         const std::filesystem::path& distributions) {
        return run_released([&] {
          if (command == "calibrate") return calibrate_inputs(files);
          const std::filesystem::path& file = files.at(0);
          if (command == "fit") return fit_inputs(prepare_fit(file, FitOptions{}));
          const Scene scene = read_scene(file);
          return command == "study" ? study_inputs(scene, distributions) : scene_inputs(scene);
        });
      },
      py::arg("command"), py::arg("files"), py::arg("distributions"));
  // The files a campaign processed from `campaign` (a campaign file) or `scenes` read.
  m.def(
      "_campaign_inputs",
      [](const std::optional<std::filesystem::path>& campaign,
         const std::vector<std::filesystem::path>& scenes) {
        return run_released(
            [&] { return process_campaign_inputs(campaign_options(campaign, scenes)); });
      },
      py::arg("campaign"), py::arg("scenes"));
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

}  // namespace shpb::python
