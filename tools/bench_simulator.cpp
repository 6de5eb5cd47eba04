// Benchmark (not a test) of the simulator: for each scene given, the median wall time of
// several runs, node updates per second, node updates against the full model (causal economy),
// and asynchronous against global stepping — at the same mesh (time ratio and incident-plateau
// error of each) and at equal error (gauge error against the study's reference, global refined
// until it is as accurate) — plus the raw element-update rate of elastic bars. Build: cmake --build
// build --target bench_simulator; run: build/bench_simulator [--repeat N] [--same-mesh-only]
// experiments/*/scene.json (tools/bench.sh does both); --asynchronous-only: the asynchronous line
// alone (e.g. under valgrind --tool=callgrind, for the instructions of one scene's runs);
// --tolerance TOL (e.g. 0.03): also each scene at the meshes and Courant number that tolerance
// chooses (model/mesh_choice.hpp) beside its automatic meshes: CPU time and the gauge error
// against the study's reference, recorded (study/recorded_error.hpp) and point-sampled (the
// study's `error` column); --defaults: a table of each scene's default run before (automatic
// meshes) and now (the default tolerance): solve time and gauge error against the reference, and
// the mesh choice's CPU made afresh, searched again with the integrals remembered, and the same
// scene's choice found again.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/median.hpp"
#include "model/front_error.hpp"
#include "model/mesh_choice.hpp"
#include "model/mesh_error_model.hpp"
#include "model/scene_validation.hpp"
#include "solver/contact.hpp"
#include "solver/simulation.hpp"
#include "study/pareto_front.hpp"
#include "study/recorded_error.hpp"
#include "study/reference.hpp"
#include "study/sweep.hpp"

using namespace shpb;

namespace {

// Relative error of the incident plateau (15–85 % of the pulse) against V/(2c0), for a striker
// and incident bar of equal impedance; NaN when not applicable.
double incident_error(const Scene& scene, const SimulationResult& r) {
  if (scene.bars.size() < 2 || scene.bars[1].gauges.empty()) return std::nan("");
  const BarSpec& s = scene.bars[0];
  const BarSpec& b = scene.bars[1];
  if (std::abs(s.impedance_kg_s() / b.impedance_kg_s() - 1) > 1e-9) return std::nan("");
  const double expected = -s.velocity_m_s / (2 * s.material.wave_speed_m_s());
  const auto& x = r.gauges.column(b.gauges.front().name);
  long first = -1, last = -1;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const bool in = x[k] / expected > 0.5;
    if (in && first < 0) first = static_cast<long>(k);
    if (first >= 0 && !in) break;
    if (in) last = static_cast<long>(k);
  }
  if (first < 0) return std::nan("");
  const long a = first + (last - first) * 15 / 100, e = first + (last - first) * 85 / 100;
  double sum = 0;
  for (long k = a; k <= e; ++k) sum += x[k];
  return std::abs(sum / (e - a + 1) / expected - 1);
}

// Wall time of the solve (summary's wall_time_s) and the process CPU time of the whole call;
// on a loaded machine the CPU time is the steadier figure.
struct Timing {
  double wall_s;
  double cpu_s;
  SimulationResult last;
};

Timing run(const Scene& scene, const SimulationOptions& options, int repeat) {
  std::vector<double> walls, cpus;
  SimulationResult r;
  for (int i = 0; i < repeat; ++i) {
    const std::clock_t c0 = std::clock();
    r = simulate(scene, options);
    cpus.push_back(double(std::clock() - c0) / CLOCKS_PER_SEC);
    walls.push_back(r.wall_time_s);
  }
  return {median(walls), median(cpus), std::move(r)};
}

// Global stepping refined (mesh factor 1, 2, 4, 8 of every bar) until its gauge error against the
// study's reference (exact or fine mesh, study/reference.hpp) is at most the asynchronous run's;
// the CPU time at that error is interpolated log–log between the two bracketing meshes, as the
// study's Pareto front does. At the same mesh global stepping is less accurate (its bars run at
// Courant c·Δt_specimen/h ≪ 1), so the same-mesh ratio compares unequal errors.
void equal_error(const Scene& scene, const Timing& async, const Timing& global_same_mesh,
                 const SimulationOptions& options) {
  const std::clock_t c0 = std::clock();
  std::optional<GaugeReference> reference = exact_reference(scene);
  if (!reference) reference = fine_mesh_reference(scene, kReferenceResolution, options);
  const double reference_cpu_s = double(std::clock() - c0) / CLOCKS_PER_SEC;
  const double async_error = gauge_error(async.last.gauges, *reference);
  std::vector<double> errors, costs;
  std::string runs;
  for (double factor : {1.0, 2.0, 4.0, 8.0}) {
    Timing g = global_same_mesh;
    if (factor > 1) {
      Scene refined = scene_at_resolution(scene, factor);
      refined.simulation.stepping = Stepping::kGlobal;
      g = run(refined, options, 1);
    }
    errors.push_back(g.last.stable ? gauge_error(g.last.gauges, *reference) : std::nan(""));
    costs.push_back(g.cpu_s);
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s%gx mesh %.3g in %.3g s", runs.empty() ? "" : ", ", factor,
                  errors.back(), g.cpu_s);
    runs += buf;
    if (errors.back() <= async_error) break;
  }
  std::printf("  equal error (gauge L2 error against %s, %.1f s to compute):\n",
              reference->exact ? "the exact solution" : "a fine-mesh run", reference_cpu_s);
  std::printf("    asynchronous 1x mesh: error %.3g in %.3g s CPU; global: %s\n", async_error,
              async.cpu_s, runs.c_str());
  const std::optional<double> cost = errors.front() <= async_error
                                         ? std::optional<double>(costs.front())
                                         : cost_at_error(errors, costs, async_error);
  if (cost)
    std::printf("    global at the asynchronous error: %.3g s CPU: asynchronous is x%.0f faster\n",
                *cost, *cost / async.cpu_s);
  else
    std::printf(
        "    global did not reach the asynchronous error by 8x mesh: asynchronous is more "
        "than x%.0f faster\n",
        costs.back() / async.cpu_s);
}

}  // namespace

// The scene at its automatic meshes and at the meshes `tolerance` chooses, side by side.
void tolerance_against_default(const Scene& scene, double tolerance,
                               const SimulationOptions& options, const Timing& automatic,
                               int repeat) {
  const auto exact = exact_reference(scene);
  const GaugeReference ref =
      exact ? *exact : fine_mesh_reference(scene, kReferenceResolution, options);
  Scene chosen = scene;
  chosen.simulation.tolerance = tolerance;
  resolve_scene(chosen);
  const Timing t = run(chosen, options, repeat);
  const auto line = [&](const char* label, const Timing& x, bool filtered) {
    std::printf(
        "    %-22s %7.2f ms wall, %7.2f ms CPU, %10lld node updates, gauge error %.3f %% recorded, "
        "%.3f %% point-sampled%s\n",
        label, x.wall_s * 1e3, x.cpu_s * 1e3, x.last.node_updates,
        100 * recorded_gauge_error(x.last.gauges, ref, filtered),
        100 * gauge_error(x.last.gauges, ref), x.last.stable ? "" : " UNSTABLE");
  };
  std::printf("  --tolerance %g %% against the automatic meshes (error against %s):\n",
              100 * tolerance, ref.description.c_str());
  line("automatic meshes", automatic, gauges_filtered(scene.simulation));
  line("tolerance's meshes", t, gauges_filtered(chosen.simulation));
  std::printf("    tolerance's choice: Courant %g, elements",
              chosen.simulation.courant.value_or(0));
  for (const BarSpec& b : chosen.bars) std::printf(" %d", b.elements);
  std::printf("; CPU time x%.2f the automatic meshes'\n", t.cpu_s / automatic.cpu_s);
}

// The scene of `file`, or nothing (a line says why) when it cannot be read: the table goes on.
std::optional<Scene> read_or_skip(const std::string& file) {
  try {
    return read_scene(file);
  } catch (const std::exception& e) {
    std::printf("%s: skipped (%s)\n", file.c_str(), e.what());
    return std::nullopt;
  }
}

// One row per scene: the automatic meshes (the default before the default tolerance) against the
// default run's (kDefaultTolerance, model/scene_validation.hpp resolve_scene): median solve time
// (summary.json's wall_time_s), CPU time, node updates, and the gauge error against the study's
// reference (exact, or the 8 x run of the automatic meshes) as recorded (study/recorded_error.hpp).
void defaults_table(const std::vector<std::string>& files, const SimulationOptions& options,
                    int repeat) {
  std::printf("default run: automatic meshes (before) against the default tolerance %g %% (now)\n",
              100 * kDefaultTolerance);
  std::printf("%-28s | %9s %9s %10s %8s | %9s %9s %9s %9s %9s %10s %8s %9s\n", "experiment",
              "wall_ms", "cpu_ms", "updates", "error", "fresh_ms", "search_ms", "found_ms",
              "wall_ms", "cpu_ms", "updates", "error", "predicted");
  for (const std::string& file : files) {
    const auto read = read_or_skip(file);
    if (!read) continue;
    Scene automatic = *read;
    RunOptions none;
    none.default_tolerance = false;
    resolve_scene(automatic, none);
    // The mesh choice's CPU time (resolve_scene: validation and, with the default, the error
    // model's search), median of `repeat`: a run pays it before its solve. Made afresh (nothing
    // remembered, as in a process of its own); searched again with the model's integrals
    // remembered, as a study or a velocity sweep searches (model/front_error.hpp); and the same
    // scene's choice found again, as a loop of runs of one scene finds it (model/mesh_choice.hpp).
    Scene now;
    enum Remembered { kNothing, kIntegrals, kChoices };
    std::vector<double> times[3];
    for (const Remembered remembered : {kNothing, kIntegrals, kChoices})
      for (int i = 0; i < repeat; ++i) {
        if (remembered == kNothing) forget_front_errors();
        if (remembered != kChoices) forget_mesh_choices();
        now = *read;
        const std::clock_t c0 = std::clock();
        resolve_scene(now);
        times[remembered].push_back(double(std::clock() - c0) / CLOCKS_PER_SEC);
      }
    const std::string name = std::filesystem::path(file).parent_path().filename().string();
    if (!now.simulation.tolerance) {
      std::printf("%-28s | automatic meshes, unchanged: %s\n", name.c_str(),
                  now.simulation.tolerance_withheld.c_str());
      continue;
    }
    const auto exact = exact_reference(automatic);
    const GaugeReference ref =
        exact ? *exact : fine_mesh_reference(automatic, kReferenceResolution, options);
    const Timing a = run(automatic, options, repeat), n = run(now, options, repeat);
    const auto error = [&](const Timing& t, const Scene& s) {
      return t.last.stable
                 ? 100 * recorded_gauge_error(t.last.gauges, ref, gauges_filtered(s.simulation))
                 : std::nan("");
    };
    std::printf(
        "%-28s | %9.2f %9.2f %10.3g %7.2f%% | %9.2f %9.2f %9.3f %9.2f %9.2f %10.3g %7.2f%% "
        "%8.2f%%\n",
        name.c_str(), a.wall_s * 1e3, a.cpu_s * 1e3, double(a.last.node_updates),
        error(a, automatic), median(times[kNothing]) * 1e3, median(times[kIntegrals]) * 1e3,
        median(times[kChoices]) * 1e3, n.wall_s * 1e3, n.cpu_s * 1e3, double(n.last.node_updates),
        error(n, now), 100 * predict_gauge_error(now, discretize(now)).total);
    std::fflush(stdout);
  }
}

int main(int argc, char** argv) {
  int repeat = 5;
  bool equal_error_comparison = true;
  bool asynchronous_only = false;
  double tolerance = 0;
  bool defaults = false;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeat" && i + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++i]));
    else if (a == "--same-mesh-only")
      equal_error_comparison = false;
    else if (a == "--asynchronous-only")
      asynchronous_only = true;
    else if (a == "--tolerance" && i + 1 < argc)
      tolerance = std::atof(argv[++i]);
    else if (a == "--defaults")
      defaults = true;
    else
      scenes.push_back(a);
  }
  SimulationOptions economy;
  economy.record_field = false;
  SimulationOptions full = economy;
  full.full_model = true;
  if (defaults) {
    defaults_table(scenes, economy, repeat);
    return 0;
  }

  for (const std::string& file : scenes) {
    auto read = read_or_skip(file);
    if (!read) continue;
    Scene scene = std::move(*read);
    if (std::none_of(scene.bars.begin(), scene.bars.end(),
                     [](const BarSpec& bar) { return bar.velocity_m_s != 0; })) {
      std::printf(
          "%s: skipped (no bar moves: the scene gives no striker velocity; shpb compare "
          "infers one from the measurement)\n",
          file.c_str());
      continue;
    }
    scene.simulation.stepping = Stepping::kAsynchronous;
    const Timing a = run(scene, economy, repeat);
    if (asynchronous_only) {
      std::printf("%s: asynchronous %.2f ms wall, %.2f ms CPU (medians of %d), energy error %.2g\n",
                  file.c_str(), a.wall_s * 1e3, a.cpu_s * 1e3, repeat, a.last.energy_error);
      if (tolerance > 0) tolerance_against_default(scene, tolerance, economy, a, repeat);
      continue;
    }
    const Timing af = run(scene, full, 1);
    scene.simulation.stepping = Stepping::kGlobal;
    const Timing g = run(scene, economy, std::max(1, repeat / 2));
    scene.simulation.stepping = Stepping::kAsynchronous;
    std::printf("%s (%s)\n", file.c_str(), scene.name.c_str());
    std::printf(
        "  asynchronous: %.2f ms wall, %.2f ms CPU (medians of %d), %lld node updates "
        "(%.3g/s of CPU), energy error %.2g%s\n",
        a.wall_s * 1e3, a.cpu_s * 1e3, repeat, a.last.node_updates, a.last.node_updates / a.cpu_s,
        a.last.energy_error, a.last.stable ? "" : " UNSTABLE");
    bool bonded = false;  // finite links are unilateral: a bonded specimen would come loose
    for (std::size_t k = 0; k + 1 < scene.bars.size(); ++k)
      bonded = bonded || interface_method(scene.contact, k) == ContactMethod::kBonded;
    if (bonded) {
      std::printf(
          "  finite localized links: not applicable (bonded interfaces; finite links are "
          "unilateral)\n");
    } else {
      // Finite localized links at the default ε_s and R (contact_localized_finite.cpp) against
      // the scene as given (the rigid-link limit unless it sets penalty values), asynchronous.
      Scene finite = scene;
      finite.contact.method = ContactMethod::kLocalizedBipenalty;
      for (InterfaceOverride& o : finite.contact.interfaces) o.method.reset();
      finite.contact.penalty.stiffness_factor = kDefaultStiffnessFactor;
      finite.contact.penalty.mass_ratio = kDefaultMassRatio;
      const Timing f = run(finite, economy, repeat);
      std::printf(
          "  finite localized links (eps_s = %g EA/h, R = %g R_crit), asynchronous: %.2f ms "
          "wall, %.2f ms CPU, x%.2f the scene's contact in CPU time, energy error %.2g%s\n",
          kDefaultStiffnessFactor, kDefaultMassRatio, f.wall_s * 1e3, f.cpu_s * 1e3,
          f.cpu_s / a.cpu_s, f.last.energy_error, f.last.stable ? "" : " UNSTABLE");
    }
    {
      // The specimen's step plan and the instants of a bar at rest, side by side in one build:
      // the fixed plan at (1 − e_max) with every instant taken (the path before
      // solver/step_control.hpp and scheduler rule 10) against the default.
      SimulationOptions previous = economy;
      previous.adaptive_step = false;
      previous.skip_at_rest = false;
      const Timing p = run(scene, previous, repeat);
      long steps_a = 0, steps_p = 0;
      for (std::size_t i = 0; i < a.last.bars.size(); ++i)
        if (scene.specimen && *scene.specimen == i) {
          steps_a = a.last.bars[i].steps;
          steps_p = p.last.bars[i].steps;
        }
      double num = 0, den = 0;
      for (std::size_t c = 0; c < a.last.gauges.values.size(); ++c)
        for (std::size_t k = 0; k < std::min(a.last.gauges.samples(), p.last.gauges.samples());
             ++k) {
          const double d = a.last.gauges.values[c][k] - p.last.gauges.values[c][k];
          num += d * d;
          den += p.last.gauges.values[c][k] * p.last.gauges.values[c][k];
        }
      std::printf(
          "  specimen step from its shortest element, instants at rest skipped, against the fixed "
          "plan and every instant: %.2f against %.2f ms CPU (x%.2f), specimen steps %ld against "
          "%ld, gauges %.2g apart (L2)\n",
          a.cpu_s * 1e3, p.cpu_s * 1e3, p.cpu_s / a.cpu_s, steps_a, steps_p,
          den > 0 ? std::sqrt(num / den) : 0.0);
    }
    std::printf(
        "  causal economy: %lld of %lld node updates of the full model (saves %.1f %%); "
        "full model %.2f ms\n",
        a.last.node_updates, af.last.node_updates,
        100.0 * (1.0 - double(a.last.node_updates) / double(af.last.node_updates)),
        af.wall_s * 1e3);
    std::printf(
        "  global: %.2f ms wall, %.2f ms CPU, %lld node updates; global/asynchronous: "
        "CPU time x%.1f, updates x%.1f\n",
        g.wall_s * 1e3, g.cpu_s * 1e3, g.last.node_updates, g.cpu_s / a.cpu_s,
        double(g.last.node_updates) / double(a.last.node_updates));
    const double plateau_async = incident_error(scene, a.last);
    if (std::isnan(plateau_async))
      std::printf(
          "  incident plateau error against V/(2c0): not applicable (striker and incident "
          "bar differ in impedance or something stands between them)\n");
    else
      std::printf("  incident plateau error against V/(2c0): asynchronous %.2e, global %.2e\n",
                  plateau_async, incident_error(scene, g.last));
    if (equal_error_comparison) equal_error(scene, a, g, economy);
  }

  if (asynchronous_only) return 0;
  // Raw rate of the elastic kernel: a steel striker on a 2 m bar, every node updated.
  Scene bars;
  bars.name = "elastic bars";
  MaterialSpec steel;
  steel.density_kg_m3 = 8000;
  steel.youngs_modulus_Pa = 200e9;
  BarSpec s;
  s.name = "striker";
  s.material = steel;
  s.length_m = 0.3;
  s.area_m2 = 2.85e-4;
  s.velocity_m_s = 10;
  BarSpec b = s;
  b.name = "bar";
  b.length_m = 2.0;
  b.velocity_m_s = 0;
  b.gauges.push_back({"g", 1.0});
  bars.bars = {s, b};
  bars.simulation.duration_s = 800e-6;
  const Timing e = run(bars, full, repeat);
  std::printf(
      "elastic bars (0.3 m striker on 2 m bar, 1 mm elements, 800 us, full model): "
      "%.2f ms wall, %.2f ms CPU, %.3g element updates/s of CPU\n",
      e.wall_s * 1e3, e.cpu_s * 1e3, e.last.node_updates / e.cpu_s);
  return 0;
}
