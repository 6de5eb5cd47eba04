// `shpb validate SCENE.json [--json]`: reads and checks a scene with the checks every command
// shares (apply_overrides → validate_scene), then prints the resolved set-up
// (model/setup_report.hpp) — exactly the mesh, time steps and interface links `simulate` will use
// (discretize(), interface_model()) and, for a scene with a measurement, what `process` will read
// and use (analysis/process_setup.hpp). A scene that only processes (a bar without material) is
// checked for `process` alone.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "analysis/process_setup.hpp"
#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "core/interrupt.hpp"
#include "model/setup_report.hpp"
#include "solver/contact.hpp"

namespace shpb {
namespace {

using nlohmann::json;

// The interfaces as the run links them (solver/contact.hpp).
json interfaces_json(const Scene& scene, const ChainDiscretization& d) {
  json out = json::array();
  for (std::size_t i = 0; i + 1 < scene.bars.size(); ++i) {
    // What the run uses: the rigid-link limit ignores the penalty values; finite localized
    // links have one per side; node-to-node methods one link (no mass penalty for penalty).
    const InterfaceModel m = interface_model(scene, d, i);
    json links;
    if (m.method == ContactMethod::kLocalizedBipenalty && !m.finite_links) {
      links = "rigid-link limit";
    } else {
      const int count = m.method == ContactMethod::kLocalizedBipenalty ? 2 : 1;
      json stiffness = json::array(), mass = json::array();
      for (int k = 0; k < count; ++k) {
        stiffness.push_back(m.stiffness_N_m[k]);
        mass.push_back(m.mass_penalty_kg[k]);
      }
      links = {{"stiffness_N_m", stiffness}};
      if (m.method != ContactMethod::kPenalty) links["mass_penalty_kg"] = mass;
    }
    out.push_back({{"left", scene.bars[i].name},
                   {"right", scene.bars[i + 1].name},
                   {"method", to_string(m.method)},
                   {"gap_m", m.gap0_m},
                   {"links", links}});
  }
  return out;
}

// The set-up of a scene that simulates, the interfaces in their place.
json resolved_setup(const Scene& scene, const ChainDiscretization& d) {
  json out = resolved_setup_json(scene, d);
  if (scene.bars.size() > 1) out["interfaces"] = interfaces_json(scene, d);
  return out;
}

}  // namespace

std::string validate_setup(Scene scene, const RunOverrides& overrides) {
  const bool measured = scene.measurement && !scene.measurement->channels.empty();
  const auto no_material = std::find_if(scene.bars.begin(), scene.bars.end(),
                                        [](const BarSpec& b) { return !b.has_material; });
  json setup;
  if (no_material != scene.bars.end() && measured) {
    // Only `process` runs on it: nothing to mesh.
    setup = scene_setup_json(scene, nullptr);
    setup["simulation"] = "bar \"" + no_material->name + "\" has no material (only process runs)";
    setup["warnings"] = json::array();
  } else {
    Scene automatic = scene;  // for the cost of the tolerance's meshes against today's
    setup = resolved_setup(scene, apply_overrides(overrides, scene));
    if (scene.simulation.tolerance) {
      RunOverrides o = overrides;
      o.tolerance.reset();
      o.default_tolerance = false;
      automatic.simulation.tolerance.reset();
      setup["cost_against_automatic"] = setup["node_updates_estimate"].get<double>() /
                                        apply_overrides(o, automatic).node_updates_estimate;
    }
  }
  if (measured) {
    // A record not there (kept elsewhere) stays a warning, as for simulate; a record that is
    // there is read as process reads it.
    std::filesystem::path missing;
    std::error_code ec;
    for (const ChannelSpec& c : scene.measurement->channels) {
      const auto& f = c.file.empty() ? scene.measurement->file : c.file;
      if (missing.empty() && !std::filesystem::exists(f, ec)) missing = f;
    }
    if (missing.empty()) {
      setup["process"] = process_setup(scene);
    } else {
      bool said = false;  // scene_warnings names a missing measurement.file already
      for (const auto& w : setup["warnings"])
        said = said || w.get<std::string>().find(missing.string()) != std::string::npos;
      if (!said)
        setup["warnings"].push_back("measurement file " + missing.string() +
                                    " not found (process and compare will need it)");
    }
  }
  throw_if_interrupted();  // a signal during the checks: exit 130, not a report
  return setup.dump(2);
}

int run_validate(const ValidateArgs& args) {
  // Its plan block too, as every command reads it.
  const std::string setup = validate_setup(read_scene(args.scene), args.overrides);
  if (args.json)
    std::printf("%s\n", setup.c_str());
  else
    print_setup_table(json::parse(setup));
  return 0;
}

Command add_validate_command(CLI::App& app) {
  struct Options {
    ValidateArgs args;
    RunOptionText run;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "validate",
      "Check a scene and print the resolved set-up (materials, meshes, time steps, "
      "Courant numbers, gauges, interfaces) without running it");
  cmd->add_option("scene", o->args.scene, "Scene JSON file")->required();
  cmd->add_flag("--json", o->args.json, "Print the resolved set-up as JSON");
  add_run_options(cmd, o->args.overrides, o->run);
  return {cmd, [o] {
            resolve_run_options(o->args.overrides, o->run);
            return run_validate(o->args);
          }};
}

}  // namespace shpb
