// shpb study SCENE.json -o DIR --sweep pareto|stability: accuracy against cost of every
// contact method × stepping × mesh resolution (pareto.csv), or the stability map of the contact
// methods over penalty stiffness, Courant number and mass ratio (stability.csv,
// stability_boundary.csv); summary.json says what was compared with what. Written atomically.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/commands.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/output_folder.hpp"
#include "study/parallel_runner.hpp"
#include "study/pareto_front.hpp"
#include "study/pareto_sweep.hpp"
#include "study/stability_sweep.hpp"

namespace shpb {

namespace {

using Json = nlohmann::ordered_json;

// "done/total runs" on stderr: redrawn in place on a terminal, every 10 % otherwise.
std::function<void(std::size_t, std::size_t)> progress_printer(bool quiet, std::string what) {
  if (quiet) return {};
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  return [tty, what, last = -1](std::size_t done, std::size_t total) mutable {
    const int pct = static_cast<int>(100.0 * done / total);
    if (tty) {
      std::fprintf(stderr, "\rstudy %s: %zu/%zu runs (%d%%)", what.c_str(), done, total, pct);
      if (done == total) std::fprintf(stderr, "\n");
    } else if (pct / 10 != last / 10 || done == total) {
      last = pct;
      std::fprintf(stderr, "study %s: %zu/%zu runs (%d%%)\n", what.c_str(), done, total, pct);
    }
  };
}

// A CSV field: shortest round-trip double, empty for a non-finite value (undefined, e.g. the
// error of an unstable run).
std::string field(double v) { return std::isfinite(v) ? format_double(v) : std::string(); }

Json case_json(const ParetoCase& c) {
  return Json{{"method", to_string(c.method)},
              {"stepping", to_string(c.stepping)},
              {"resolution", c.resolution}};
}

// Speed of localized-bipenalty asynchronous against localized-bipenalty global at equal error:
// the global runs' wall time (and node updates) interpolated at each asynchronous run's error.
Json speed_ratios(const ParetoStudy& study) {
  std::vector<double> err, wall, updates;
  for (const ParetoRow& r : study.rows)
    if (r.run.method == ContactMethod::kLocalizedBipenalty && r.run.stepping == Stepping::kGlobal &&
        std::isfinite(r.error)) {
      err.push_back(r.error);
      wall.push_back(r.wall_time_s);
      updates.push_back(static_cast<double>(r.node_updates));
    }
  Json out = Json::array();
  for (const ParetoRow& r : study.rows) {
    if (r.run.method != ContactMethod::kLocalizedBipenalty ||
        r.run.stepping != Stepping::kAsynchronous || !std::isfinite(r.error))
      continue;
    Json j{{"resolution", r.run.resolution}, {"error", r.error}, {"wall_time_s", r.wall_time_s}};
    const auto w = cost_at_error(err, wall, r.error);
    const auto u = cost_at_error(err, updates, r.error);
    j["global_wall_time_s_at_equal_error"] = w ? Json(*w) : Json(nullptr);
    j["wall_time_ratio_global_to_asynchronous"] = w ? Json(*w / r.wall_time_s) : Json(nullptr);
    j["node_update_ratio_global_to_asynchronous"] =
        u ? Json(*u / static_cast<double>(r.node_updates)) : Json(nullptr);
    out.push_back(j);
  }
  return out;
}

void write_pareto(const ParetoStudy& study, const Scene& scene, int threads, double wall_s,
                  const std::filesystem::path& dir) {
  {
    std::ostringstream csv;
    csv << "method,stepping,resolution,error,wall_time_s,node_updates,stable\n";
    for (const ParetoRow& r : study.rows)
      csv << to_string(r.run.method) << ',' << to_string(r.run.stepping) << ','
          << format_double(r.run.resolution) << ',' << field(r.error) << ','
          << format_double(r.wall_time_s) << ',' << r.node_updates << ',' << (r.stable ? 1 : 0)
          << '\n';
    write_text_file(dir / "pareto.csv", csv.str());
  }
  std::vector<double> err, wall, updates;
  for (const ParetoRow& r : study.rows) {
    err.push_back(r.error);
    wall.push_back(r.wall_time_s);
    updates.push_back(static_cast<double>(r.node_updates));
  }
  const std::vector<bool> by_wall = pareto_front(err, wall),
                          by_updates = pareto_front(err, updates);
  Json front_wall = Json::array(), front_updates = Json::array(), unstable = Json::array();
  for (std::size_t i = 0; i < study.rows.size(); ++i) {
    if (by_wall[i]) front_wall.push_back(case_json(study.rows[i].run));
    if (by_updates[i]) front_updates.push_back(case_json(study.rows[i].run));
    if (!study.rows[i].stable) {
      Json j = case_json(study.rows[i].run);
      j["failure"] = study.rows[i].failure;
      unstable.push_back(j);
    }
  }
  Json j;
  j["version"] = SHPB_VERSION;
  j["scene"] = scene.name;
  j["sweep"] = "pareto";
  j["error"] = "relative L2 norm of the gauge strains against the reference, all gauges";
  j["reference"] = study.reference;
  j["reference_exact"] = study.reference_exact;
  if (!study.reference_exact) j["reference_wall_time_s"] = study.reference_wall_time_s;
  j["runs"] = study.rows.size();
  j["threads"] = threads;
  j["wall_time_s"] = wall_s;
  j["pareto_front_wall_time"] = front_wall;
  j["pareto_front_node_updates"] = front_updates;
  j["localized_bipenalty_asynchronous_against_global"] = speed_ratios(study);
  j["unstable"] = unstable;
  write_text_file(dir / "summary.json", j.dump(2) + "\n");
}

void write_stability(const StabilityStudy& study, const Scene& scene, int threads, double wall_s,
                     const std::filesystem::path& dir) {
  {
    std::ostringstream csv;
    csv << "method,stiffness_factor,mass_ratio,courant,energy_growth,stable\n";
    for (const StabilityRow& r : study.rows)
      csv << to_string(r.point.method) << ',' << format_double(r.point.stiffness_factor) << ','
          << (r.point.method == ContactMethod::kPenalty ? "" : format_double(r.point.mass_ratio))
          << ',' << format_double(r.point.courant) << ',' << field(r.verdict.energy_growth) << ','
          << (r.verdict.stable ? 1 : 0) << '\n';
    write_text_file(dir / "stability.csv", csv.str());
  }
  {
    std::ostringstream csv;
    csv << "method,link,stiffness_factor,mass_ratio,critical_courant,closed_form_courant\n";
    for (const StabilityBoundary& b : study.boundaries)
      csv << to_string(b.line.method) << ',' << (b.line.tied ? "tied" : "unilateral") << ','
          << format_double(b.line.stiffness_factor) << ','
          << (b.line.method == ContactMethod::kPenalty ? "" : format_double(b.line.mass_ratio))
          << ','
          << (b.critical_courant <= kBoundaryCourantMin ? "" : format_double(b.critical_courant))
          << ',' << format_double(b.closed_form_courant) << '\n';
    write_text_file(dir / "stability_boundary.csv", csv.str());
  }
  Json j;
  j["version"] = SHPB_VERSION;
  j["scene"] = scene.name;
  j["sweep"] = "stability";
  j["probe"] = study.probe;
  j["unstable_when"] = "total energy above " + format_double(kUnstableEnergyGrowth) +
                       " x its initial value, or a non-finite value";
  j["stiffness_factor"] = "penalty stiffness / (EA/h) of the stiffer neighbour";
  j["mass_ratio"] = "R / R_crit, R = stiffness / mass penalty, R_crit = (2 c/h)^2";
  j["closed_form_courant"] =
      "penalty: sqrt(2/(1+sqrt(1+4 s^2))), exact limit of two lumped bars joined by the penalty "
      "spring; bipenalty: 1 for R <= R_crit, sqrt(R_crit/R) (the 2/sqrt(R) step) above";
  j["boundary_range"] = {kBoundaryCourantMin, kBoundaryCourantMax};
  j["critical_courant"] =
      "largest stable Courant number by bisection in boundary_range; empty: unstable at its lower "
      "end, its upper end: stable throughout; link tied: penalty or node-to-node bipenalty acting "
      "in "
      "tension too (the linear system of the closed forms), unilateral: as used";
  j["points"] = study.rows.size();
  j["threads"] = threads;
  j["wall_time_s"] = wall_s;
  write_text_file(dir / "summary.json", j.dump(2) + "\n");
}

}  // namespace

int run_study(const StudyArgs& args) {
  Scene scene = read_scene(args.scene);  // InputError → exit 2, nothing written
  apply_overrides(args.overrides, scene);
  OutputFolder out(args.output, "study", scene_inputs(scene));
  std::vector<ContactMethod> methods;
  std::vector<Stepping> steppings;
  if (args.overrides.contact) methods.push_back(*args.overrides.contact);
  if (args.overrides.stepping) steppings.push_back(*args.overrides.stepping);
  const int threads = resolve_threads(args.overrides.threads);
  const auto cancel = [] { return interrupted(); };
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  if (args.sweep == "stability") {
    const StabilityStudy study = run_stability_sweep(
        scene, methods, threads, progress_printer(args.overrides.quiet, "stability"), cancel);
    write_stability(study, scene, threads, elapsed(), out.path());
  } else {
    const ParetoStudy study =
        run_pareto_sweep(scene, pareto_cases(methods, steppings), threads,
                         progress_printer(args.overrides.quiet, "pareto"), cancel);
    write_pareto(study, scene, threads, elapsed(), out.path());
  }
  const double wall = elapsed();
  out.commit();
  if (!args.overrides.quiet)
    std::fprintf(stderr, "study %s of %s in %.3g s on %d threads; wrote %s\n", args.sweep.c_str(),
                 scene.name.c_str(), wall, threads, out.final_path().string().c_str());
  return 0;
}

}  // namespace shpb
