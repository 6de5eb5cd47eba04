#include "solver/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/checked_write.hpp"
#include "core/clock.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/json_numbers.hpp"
#include "model/calibration.hpp"
#include "model/laws/johnson_cook_law.hpp"
#include "model/mesh_error_model.hpp"
#include "model/scene_checks.hpp"
#include "model/specimen_response.hpp"
#include "output_schema.hpp"
#include "solver/chain.hpp"
#include "solver/end_segment.hpp"
#include "solver/recorders.hpp"
#include "solver/scheduler.hpp"
#include "solver/step_control.hpp"
#include "version.hpp"

namespace shpb {

namespace {

// Low-pass time of the radial-inertia ε̈, in elastic transits L/c of the bar (solver/bar.hpp).
constexpr double kInertiaFilterTransits = 0.25;

// Steps, kinematics, face friction and radial inertia of bar i (solver/bar.hpp; docs/methods.md
// §8). `adaptive`: the specimen's step follows its shortest element (step_control.hpp) when it is
// finite-strain without face friction or radial inertia. Measured, those two and a pulse shaper
// depend on the step itself (the fixed plan at e_max 0.25 instead of 0.5 moves the friction test's
// peak stress by 12 %; a copper shaper at e_max 0.14–0.3 loses 0.7–4.6 % of the energy), so they
// keep the fixed plan until that is understood.
void configure_bar(BarModel& bar, const Scene& scene, std::size_t i, bool adaptive) {
  const double courant = scene.simulation.courant.value_or(kDefaultCourant);
  const double critical_step_s = bar.element_length_m / bar.wave_speed_m_s;
  bar.reference_step_s = courant * critical_step_s;
  bar.own_step_s = bar_courant(scene, i, courant) * critical_step_s;  // discretize()'s
  if (!bar.law) return;
  bar.finite_strain = scene.simulation.finite_strain;
  bar.min_stretch = 1 - scene.simulation.max_strain.value_or(kDefaultMaxStrain);
  // Friction on the faces of a bar squeezed between two others, the specimen or a pulse shaper
  // (the closed form is a Kolsky specimen's, docs/methods.md §8.2); two faces of different μ act
  // through their mean (first order).
  const bool squeezed =
      (scene.specimen && *scene.specimen == i) || squeezed_bar(i, scene.bars.size());
  if (!squeezed) return;
  const double left = i > 0 ? interface_friction(scene.contact, i - 1) : 0.0;
  const double right = i + 1 < scene.bars.size() ? interface_friction(scene.contact, i) : 0.0;
  bar.friction_factor_per_aspect = friction_factor_per_aspect(0.5 * (left + right));
  if (scene.bars[i].inertia) {  // the reader allows it on a squeezed bar only
    bar.radial_inertia_density_kg_m3 = bar.density_kg_m3;
    bar.inertia_filter_s =
        kInertiaFilterTransits * bar.element_length_m * bar.elements() / bar.wave_speed_m_s;
  }
  // The specimen only: a pulse shaper keeps its fixed step (its ties' end segments, §3.6).
  bar.adaptive_step = adaptive && scene.specimen && *scene.specimen == i && bar.finite_strain &&
                      bar.friction_factor_per_aspect == 0 && bar.radial_inertia_density_kg_m3 == 0;
}

// The material bar i gives its law: the scene's specimen's, with its default Johnson–Cook rate
// filter (model/laws/johnson_cook_law.hpp).
MaterialSpec law_material(const Scene& scene, std::size_t i) {
  const BarSpec& spec = scene.bars[i];
  const bool specimen = scene.specimen && *scene.specimen == i;
  return specimen ? specimen_law_material(spec.material, spec.length_m) : spec.material;
}

// docs/methods.md §7: lumped central difference moves information by exactly one node per step, and
// every disturbance of the last bar enters at its left end. A node j right of the rightmost node
// k that is recorded (gauges) or coupled (node 0) is first disturbed at step ≥ s_k + (j − k) and
// can act back on k at step ≥ s_k + 2(j − k): beyond k + N/2 (N instants in the run) nothing can
// come back before the end, so the bar is cut there and ended with a dashpot (non-reflecting).
// Recorded values are unchanged to the last bit.
void cut_last_bar(Chain& c, const Scene& scene, bool adaptive) {
  BarModel& bar = c.bars.back();
  const BarSpec& spec = scene.bars.back();
  int k = 0;
  for (const GaugeSpec& g : spec.gauges)
    k = std::max(k, static_cast<int>(std::floor(g.position_m / bar.element_length_m + 0.5)) + 2);
  // At most this many instants: time_step_s is the smallest step an adaptive chain may take.
  const long instants = static_cast<long>(std::ceil(c.end_tau_s / bar.time_step_s - 1e-9)) + 1;
  const long keep = k + instants / 2 + 2;  // nodes kept
  if (keep >= bar.nodes) return;
  const int elements = static_cast<int>(keep - 1);
  const int full_nodes = bar.nodes;
  bar = make_bar_model(spec.name, law_material(scene, scene.bars.size() - 1),
                       bar.element_length_m * elements, spec.area_m2, elements, bar.time_step_s,
                       spec.velocity_m_s);
  bar.full_nodes = full_nodes;
  bar.dashpot_right = true;
  configure_bar(bar, scene, scene.bars.size() - 1, adaptive);
  c.states.back() = make_bar_state(bar, false);
}

Chain build_chain(const Scene& scene, const ChainDiscretization& d, bool full_model, bool adaptive,
                  bool law_specimen_segments) {
  Chain c;
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    const BarSpec& spec = scene.bars[i];
    c.bars.push_back(make_bar_model(spec.name, law_material(scene, i), spec.length_m, spec.area_m2,
                                    d.bars[i].elements, d.bars[i].time_step_s, spec.velocity_m_s));
    configure_bar(c.bars.back(), scene, i, adaptive);
    c.states.push_back(make_bar_state(c.bars.back(), full_model));
  }
  // Until the first contact the bars fly rigidly, unstrained: the run starts there, each gap
  // already closed by its flight, so that the first contact falls on an instant of every bar.
  // Started at the scene's gaps, it closed at the last instant before the meeting (contact.hpp
  // closes_within), up to a step before the clock's zero: every signal up to a step early
  // (measured: 0.45 us, 9.6 % gauge error, on a striker with a 2 mm gap at the default meshes).
  const double flight = first_contact_delay_s(scene);
  for (std::size_t k = 0; k + 1 < c.bars.size(); ++k) {
    c.interfaces.push_back(interface_model(scene, d, k));
    const double closing = scene.bars[k].velocity_m_s - scene.bars[k + 1].velocity_m_s;
    c.interfaces.back().gap0_m = std::max(0.0, scene.bars[k].gap_m - closing * flight);
    c.interface_states.emplace_back();
    c.interface_states.back().gap_m = c.interfaces.back().gap0_m;
  }
  c.contact_dissipated_J.assign(c.interfaces.size(), 0.0);
  c.end_tau_s = d.duration_s;
  for (const BarModel& b : c.bars)
    c.final_step.push_back(static_cast<long>(std::ceil(c.end_tau_s / b.time_step_s - 1e-9)));
  if (!full_model && c.bars.size() > 1) cut_last_bar(c, scene, adaptive);
  c.global_stepping = d.stepping == Stepping::kGlobal;
  plan_end_segments(c, scene, law_specimen_segments);
  plan_first_steps(c);
  return c;
}

void write_series(const std::filesystem::path& file, const TimeSeries& ts) {
  std::vector<std::string> header{schema::gauges::time_s};  // every series leads with time
  header.insert(header.end(), ts.columns.begin(), ts.columns.end());
  CsvWriter csv(file, header);
  std::vector<double> row(header.size());
  for (std::size_t k = 0; k < ts.samples(); ++k) {
    row[0] = ts.time_s[k];
    for (std::size_t c = 0; c < ts.values.size(); ++c) row[c + 1] = ts.values[c][k];
    csv.row(row);
  }
  csv.close();
}

// A run may be numerically stable and still physically meaningless: flagged here, in the result's
// warnings (printed, summary.json) or, for a specimen with no length left, as a failed run.
// Engineering strain beyond this bound is far outside any SHPB test (typically < 0.5).
constexpr double kPlausibleSpecimenStrain = 0.9;
// Interfaces interpenetrating by more than this fraction of the smaller neighbouring element:
// the contact is too soft to stand for the bars' touching faces.
constexpr double kPlausiblePenetrationElements = 0.5;
// The energy balance (kinetic + strain + dissipated against the work put in) closes to 1e-6…5e-3 in
// every shipped experiment; a larger gap means the discrete contacts did work the bars' forces did
// not. Measured causes: a light, stiff bar tied to a heavy, slow one at asynchronous steps where no
// end segment covers the tie (§3.6: before them, a 3 mm shaper of 160 elements lost 5 % in
// thousands of closings), and contacts between very coarse elements (a striker of 20 mm elements
// on a bar of 100 mm: 2–4 % with either stepping).
constexpr double kPlausibleEnergyError = 0.01;

// |fraction| in percent to three significant digits, as a person reads it.
std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", 100 * std::abs(fraction));
  return text;
}

void check_plausibility(const Scene& scene, const Chain& chain, SimulationResult& result) {
  if (scene.specimen && !result.specimen.columns.empty()) {
    double worst = 0;
    for (double e : result.specimen.column("strain")) worst = std::max(worst, std::abs(e));
    if (worst >= 1 && result.stable) {
      result.stable = false;
      result.failure = "specimen engineering strain reached " + format_double(worst) +
                       ": the specimen has no length left (the 1D model no longer applies)";
    } else if (worst > kPlausibleSpecimenStrain) {
      result.warnings.push_back("specimen engineering strain reached " + format_double(worst) +
                                " (beyond " + format_double(kPlausibleSpecimenStrain) +
                                "): the result is not physical");
    }
  }
  if (chain.max_penetration_elements > kPlausiblePenetrationElements) {
    // A rigid link creates no penetration of its own; it keeps one its ends reached between a
    // coarse neighbour's instants (≤ |ġ|Δt, docs/methods.md §3.2–3.4).
    bool compliant = false;
    for (const InterfaceModel& m : chain.interfaces)
      compliant = compliant || m.finite_links || m.method == ContactMethod::kPenalty ||
                  m.method == ContactMethod::kBipenalty;
    char text[300];
    std::snprintf(text, sizeof text,
                  "the bars interpenetrated by %.3g mm, %.3g of the smaller neighbouring element "
                  "(more than %.3g): %s",
                  chain.max_penetration_m * 1e3, chain.max_penetration_elements,
                  kPlausiblePenetrationElements,
                  compliant ? "the contact is too soft (stiffness, stiffness_factor or rise_time)"
                            : "a rigid link kept what its ends closed between a neighbour's "
                              "coarse steps; compare with \"stepping\": \"global\" or finer "
                              "meshes");
    result.warnings.push_back(text);
  }
  const std::size_t samples = result.gauges.samples();
  if (samples > 0 && samples < kMinRecordSamples)
    result.warnings.push_back("the record has only " + std::to_string(samples) +
                              " samples: raise simulation.sample_rate (or the duration) to "
                              "resolve the pulses");
  if (std::abs(result.energy_error) > kPlausibleEnergyError) {
    std::size_t most = 0;
    for (std::size_t k = 1; k < chain.interfaces.size(); ++k)
      if (chain.interface_states[k].activations > chain.interface_states[most].activations)
        most = k;
    std::string text = "the energy balance is off by " + percent(result.energy_error) +
                       " % (beyond " + format_double(100 * kPlausibleEnergyError) + " %)";
    if (!chain.interfaces.empty())
      text += "; interface " + chain.interfaces[most].name + " closed " +
              std::to_string(chain.interface_states[most].activations) + " times";
    bool unequal_steps = false;
    for (const BarState& b : chain.states)
      unequal_steps = unequal_steps || b.dt != chain.states.front().dt;
    if (unequal_steps)
      text +=
          ": a tie between bars on different steps can chatter (docs/methods.md §3.6–3.7); "
          "compare with \"stepping\": \"global\" or finer meshes";
    else
      text += ": compare with finer meshes";
    result.warnings.push_back(text);
  }
  // A bar of one element has no interior node: its waves are not resolved.
  for (std::size_t i = 0; i < chain.bars.size(); ++i)
    if (chain.bars[i].full_nodes < 3)
      result.warnings.push_back("bar \"" + chain.bars[i].name +
                                "\" has a single element: its waves are not resolved");
}

// One run of the chain; `law_specimen_segments` as plan_end_segments takes it.
SimulationResult run_chain(const Scene& scene, const ChainDiscretization& d,
                           const SimulationOptions& options, bool law_specimen_segments) {
  SimulationResult result;
  result.discretization = d;
  Chain chain =
      build_chain(scene, d, options.full_model, options.adaptive_step, law_specimen_segments);
  ChainRecorders recorders(scene, chain, d, options);

  const auto start = std::chrono::steady_clock::now();
  const ScheduleOutcome outcome = run_schedule(chain, recorders, options.progress, options.cancel,
                                               options.subcycle, options.skip_at_rest);
  result.wall_time_s = seconds_since(start);

  result.stable = outcome.stable;
  result.failure = outcome.failure;
  // Finite strain: elements shorter than the step was planned for (discretization.hpp).
  for (std::size_t i = 0; i < chain.bars.size(); ++i) {
    const BarModel& b = chain.bars[i];
    if (!b.finite_strain || chain.states[i].smallest_stretch >= b.min_stretch) continue;
    result.stable = false;
    result.beyond_planned_strain = true;
    result.failure = "bar \"" + b.name + "\" was compressed to " +
                     std::to_string(1 - chain.states[i].smallest_stretch) +
                     " engineering strain in an element, beyond the " +
                     std::to_string(1 - b.min_stretch) +
                     " its stable step was planned for: raise simulation.max_strain";
    // A contact that blew up crushes elements too (a plain penalty at its default stiffness on a
    // pulse shaper: the energy × 10): then a larger plan is not the remedy alone.
    if (!(std::abs(outcome.energy_error) <= kPlausibleEnergyError))
      result.failure += ", or look at the energy balance, off by " + percent(outcome.energy_error) +
                        " % (compare another contact method or --stepping global)";
    break;
  }
  result.energy_error = outcome.energy_error;
  result.max_penetration_m = std::max(0.0, chain.max_penetration_m);
  result.max_penetration_elements = std::max(0.0, chain.max_penetration_elements);
  recorders.finish(chain, outcome.checked_until_s, result);
  for (std::size_t i = 0; i < chain.bars.size(); ++i) {
    const BarModel& b = chain.bars[i];
    const BarState& s = chain.states[i];
    BarStatistics st;
    st.name = b.name;
    st.elements = b.full_nodes - 1;
    st.simulated_elements = b.elements();
    st.time_step_s = s.dt;  // the last (adaptive: the smallest) step
    st.steps = s.step;
    st.courant = b.courant_at(s.dt);
    st.node_updates = s.node_updates;
    // An end segment's nodes step on their clock bar's instants from the instant it started at
    // (end_segment.hpp), on the bar's before.
    st.node_updates_full_model = static_cast<long long>(s.step) *
                                 (b.full_nodes - b.segment_elements[0] - b.segment_elements[1]);
    for (const EndSegment& seg : chain.segments)
      if (seg.bar == i)
        st.node_updates_full_model +=
            static_cast<long long>(seg.bar_steps_before + chain.states[seg.clock_bar].step -
                                   seg.clock_steps_before) *
            seg.elements;
    double momentum = 0;
    for (int n = 0; n < b.nodes; ++n) momentum += b.mass_kg[n] * (s.v[n] + b.initial_velocity_m_s);
    st.final_velocity_m_s = momentum / b.total_mass_kg();
    result.node_updates += st.node_updates;
    result.node_updates_full_model += st.node_updates_full_model;
    result.bars.push_back(st);
  }
  check_plausibility(scene, chain, result);
  for (std::size_t k = 0; k < chain.interfaces.size(); ++k) {
    const InterfaceState& is = chain.interface_states[k];
    const InterfaceState::Unloading& u = is.unloading;
    InterfaceStatistics st{chain.interfaces[k].name,
                           std::string(to_string(chain.interfaces[k].method)),
                           is.activations,
                           is.releases,
                           u.release_s,
                           u.closings,
                           u.meetings,
                           chain.interfaces[k].meeting_separation_s,
                           is.peak_force_N,
                           std::isnan(u.release_s) || !(is.peak_force_N > 0)
                               ? std::numeric_limits<double>::quiet_NaN()
                               : u.largest_force_N / is.peak_force_N};
    if (const EndSegment* seg = chain.segment_at(k)) {
      st.segment_bar = chain.bars[seg->bar].name;
      st.segment_elements = seg->elements;
      st.segment_from_s = seg->from_tau;
    }
    result.interface_statistics.push_back(st);
  }
  return result;
}

// An asynchronous run whose energy balance is off by more than this, or that failed, is run again
// (SimulationOptions::stabilize): the shipped experiments close to 2.2·10⁻³ or better, and
// ordinary set-ups missed by 0.5–191 % at exit 0 (docs/validation.md, "A law specimen that stays
// elastic").
constexpr double kAsynchronousEnergyError = 5e-3;

// The element strains a run that crushed a bar past the default plan (kDefaultMaxStrain 0.5) is
// planned for next, in turn: a 1 mm × Ø10 mm copper shaper under a steel striker at 25 m/s ran
// past 0.5 (exit 3) and holds at 0.8 (energy 5.2·10⁻⁴; solve 0.10 s, 0.16 s at 0.9).
constexpr double kRetriedMaxStrains[] = {0.8, 0.9};

bool holds_energy(const SimulationResult& r) {
  return r.stable && std::abs(r.energy_error) <= kAsynchronousEnergyError;
}

// The end segments a run took from its start (a law specimen's faces take theirs once
// unloaded otherwise, end_segment.hpp).
int segment_count(const SimulationResult& r) {
  int n = 0;
  for (const InterfaceStatistics& i : r.interface_statistics)
    n += i.segment_elements > 0 && i.segment_from_s == 0;
  return n;
}

// The end segments a run of `scene` would take (plan_end_segments), before running it.
int planned_segment_count(const Scene& scene, const ChainDiscretization& d,
                          const SimulationOptions& options, bool law_specimen_segments) {
  const Chain c =
      build_chain(scene, d, options.full_model, options.adaptive_step, law_specimen_segments);
  int n = 0;
  for (std::size_t k = 0; k < c.interfaces.size(); ++k) n += c.segment_at(k) != nullptr;
  return n;
}

// One way of running a scene, of those simulate() tries in turn.
struct Attempt {
  Scene scene;
  ChainDiscretization discretization;
  bool law_specimen_segments = false;  // as plan_end_segments takes it
};

// The run simulate() keeps, of the attempts it makes. One result is held at a time, as `validate`
// estimates the memory for one run: a repeat that does not improve on the run it repeats has that
// run computed again (a run is deterministic), which only a coarse mesh that loses energy at either
// stepping pays for.
class KeptRun {
 public:
  KeptRun(Attempt first, const SimulationOptions& options)
      : attempt_(std::move(first)), options_(options), result_(run(attempt_)) {}

  const SimulationResult& result() const { return result_; }

  // Runs `next` and keeps it if it finished with a smaller energy error (or `or_if_failed` and it
  // failed too), its warnings then leading with what was done and why; the wall time counts every
  // run.
  void try_instead(Attempt next, const std::string& done, bool or_if_failed = false) {
    const bool was_stable = result_.stable;
    const double was_error = result_.energy_error;
    const std::string lost = was_stable
                                 ? "its energy balance was off by " + percent(was_error) + " %"
                                 : "it failed (" + result_.failure + ")";
    const double wall_s = result_.wall_time_s;
    if (options_.repeating) options_.repeating("repeating the run " + done + ": " + lost);
    result_ = SimulationResult{};  // its records go before the next run's are made
    SimulationResult tried = run(next);
    const bool better =
        tried.stable && (!was_stable || std::abs(tried.energy_error) < std::abs(was_error));
    if (better || (or_if_failed && !tried.stable)) {
      if (better)
        tried.warnings.insert(tried.warnings.begin(), "the run was repeated " + done + ": " + lost);
      tried.wall_time_s += wall_s;
      attempt_ = std::move(next);
      result_ = std::move(tried);
    } else {
      const double tried_s = tried.wall_time_s;
      const std::string worse = "the run was also tried " + done + ", and kept as it was: " +
                                (tried.stable ? "that run's energy balance was off by " +
                                                    percent(tried.energy_error) + " %"
                                              : "that run failed too (" + tried.failure + ")");
      tried = SimulationResult{};
      result_ = run(attempt_);
      result_.wall_time_s += wall_s + tried_s;
      result_.warnings.insert(result_.warnings.begin(), worse);
    }
  }

  SimulationResult take() { return std::move(result_); }

 private:
  SimulationResult run(const Attempt& a) const {
    return run_chain(a.scene, a.discretization, options_, a.law_specimen_segments);
  }

  Attempt attempt_;
  const SimulationOptions& options_;
  SimulationResult result_;
};

// A run repeated at global steps keeps the meshes chosen for asynchronous ones, so every bar then
// steps at the smallest bar's step, far below its Courant number 1 (methods §1.1): its gauge
// error is predicted anew and, where it exceeds the tolerance asked, said beside the repeat (a
// light shaper or specimen meshed in one element: 5–10 % predicted for 3.5 % asked, 17.7 % from
// the exact solution, docs/validation.md "Elastic chains against their exact solution").
// Re-meshing for global steps instead costs a plan's fallen-back trials far more.
void warn_global_repeat_beyond_tolerance(const Scene& scene, const ChainDiscretization& asked,
                                         SimulationResult& result) {
  const auto tolerance = scene.simulation.tolerance;
  if (!tolerance || asked.stepping == Stepping::kGlobal ||
      result.discretization.stepping != Stepping::kGlobal)
    return;
  const double predicted = predict_gauge_error(scene, result.discretization).total;
  if (!(predicted > *tolerance)) return;
  const auto after_repeat =
      result.warnings.empty() ? result.warnings.end() : result.warnings.begin() + 1;
  result.warnings.insert(
      after_repeat,
      "at global steps on the meshes chosen for asynchronous ones the bars step far below "
      "Courant number 1: the gauge error is predicted at " +
          percent(predicted) + " %, beyond the " + percent(*tolerance) +
          " % asked (--stepping global chooses meshes for global steps)");
}

}  // namespace

// The coupling of §3.4 is kept wherever it holds the energy (it is the cheapest, and what every
// shipped experiment uses); where it does not, the run is repeated with end segments at a law
// specimen's faces (§3.7: 21 of 144 ordinary compression set-ups and 35 of 90 bonded tension ones
// were repaired so, to 1.4·10⁻³ at most), else at global steps, the reference (a striker of 1–20
// elements on a finely meshed bar, a tie no segment covers: 0.6–1400 % off, 10⁻¹³ at global
// steps). The run with the better balance is kept (a coarse mesh may lose energy at either
// stepping).
SimulationResult simulate(const Scene& scene, const SimulationOptions& options) {
  const auto called = std::chrono::steady_clock::now();
  Scene planned = scene;
  ChainDiscretization d = discretize(planned);
  KeptRun kept({planned, d, false}, options);
  // A material-law bar crushed past the strain its step was planned for (a thin pulse shaper
  // under a fast striker) is planned for more, where the scene leaves simulation.max_strain to
  // the default: the steps shrink with 1 − e_max (discretization.hpp).
  for (const double strain : kRetriedMaxStrains) {
    if (!options.stabilize || scene.simulation.max_strain || !kept.result().beyond_planned_strain)
      break;
    planned.simulation.max_strain = strain;
    d = discretize(planned);
    kept.try_instead({planned, d, false},
                     "with its steps planned for an element strain of " + format_double(strain) +
                         " (simulation.max_strain, docs/methods.md §8.1)",
                     true);
  }
  const bool law_specimen = scene.specimen && !scene.bars[*scene.specimen].material.is_elastic();
  if (options.stabilize && d.stepping != Stepping::kGlobal && !holds_energy(kept.result())) {
    if (law_specimen &&
        planned_segment_count(planned, d, options, true) > segment_count(kept.result()))
      kept.try_instead({planned, d, true},
                       "with end segments at the specimen's faces (docs/methods.md §3.7)");
    if (!holds_energy(kept.result())) {
      Scene global = planned;
      global.simulation.stepping = Stepping::kGlobal;
      const ChainDiscretization global_d = discretize(global);
      kept.try_instead({std::move(global), global_d, false},
                       "at global steps (docs/methods.md §3.7)");
    }
  }
  SimulationResult result = kept.take();
  warn_global_repeat_beyond_tolerance(planned, d, result);
  // What `validate` warns of the set-up (a duration that ends before a pulse reaches its gauge,
  // nothing moving, pulses overlapping): a run of it records zeros or a mixture without it. The
  // measured record is not this command's concern.
  planned.measurement.reset();
  const std::vector<std::string> setup = scene_warnings(planned, d.duration_s);
  result.warnings.insert(result.warnings.end(), setup.begin(), setup.end());
  result.call_time_s = seconds_since(called);
  return result;
}

// summary.json's "bars" and "interfaces" entries (docs/outputs.md), keys in this order.
void to_json(nlohmann::ordered_json& j, const BarStatistics& b) {
  j = {{"name", b.name},
       {"elements", b.elements},
       {"simulated_elements", b.simulated_elements},
       {"time_step_s", b.time_step_s},
       {"steps", b.steps},
       {"courant", b.courant},
       {"node_updates", b.node_updates},
       {"node_updates_full_model", b.node_updates_full_model},
       {"final_velocity_m_s", b.final_velocity_m_s}};
}

void to_json(nlohmann::ordered_json& j, const InterfaceStatistics& i) {
  j = {{"name", i.name},
       {"method", i.method},
       {"activations", i.activations},
       {"releases", i.releases},
       {"unloading_s", number(i.unloading_s)},
       {"closings_after_unloading", i.closings_after_unloading},
       {"meetings_after_unloading", i.meetings_after_unloading},
       {"meeting_separation_s", i.meeting_separation_s},
       {"peak_force_N", i.peak_force_N},
       {"force_after_unloading_share", number(i.force_after_unloading_share)},
       {"end_segment", i.segment_elements > 0
                           ? nlohmann::ordered_json{{"bar", i.segment_bar},
                                                    {"elements", i.segment_elements},
                                                    {"from_s", i.segment_from_s}}
                           : nlohmann::ordered_json(nullptr)}};
}

void write_simulation_outputs(const SimulationResult& result, const Scene& scene,
                              const std::filesystem::path& dir) {
  write_series(dir / schema::gauges::kFile, result.gauges);
  write_series(dir / schema::interfaces::kFile, result.interfaces);
  if (scene.specimen) write_series(dir / schema::specimen::kFile, result.specimen);
  write_series(dir / schema::energy::kFile, result.energy);
  {
    namespace k = schema::field;  // the column names (src/core/output_schema.json)
    CsvWriter csv(dir / k::kFile, {k::time_s, k::x_m, k::stress_Pa});
    const FieldGrid& f = result.field;
    // Long format: each time and position repeats on many rows, so each is formatted once.
    std::vector<std::string> x_text;
    for (double x : f.x_m) x_text.push_back(format_double(x));
    std::string key;
    for (std::size_t j = 0; j < f.time_s.size(); ++j) {
      const std::string t_text = format_double(f.time_s[j]) + ",";
      for (std::size_t x = 0; x < f.x_m.size(); ++x) {
        key.assign(t_text).append(x_text[x]);
        csv.row(key, 2, std::span(&f.stress_Pa[j * f.x_m.size() + x], 1));
      }
    }
    csv.close();
  }
  write_text_file(dir / "summary.json", simulation_summary(result, scene).dump(2) + "\n");
}

nlohmann::ordered_json simulation_summary(const SimulationResult& result, const Scene& scene) {
  nlohmann::ordered_json j;
  j["version"] = kVersion;
  j["scene"] = scene.name;
  j["calibration"] = calibration_summary(scene);
  j["contact"] = std::string(to_string(scene.contact.method));
  j["stepping"] = std::string(to_string(result.discretization.stepping));
  // Material-law bars only; elastic bars are small strain either way (solver/bar.hpp).
  j["kinematics"] = std::string(enum_name(kKinematicsNames, scene.simulation.finite_strain));
  j["duration_s"] = result.discretization.duration_s;
  j["sample_rate_Hz"] = result.discretization.sample_rate_Hz;
  j["bars"] = result.bars;
  j["interfaces"] = result.interface_statistics;
  j["node_updates"] = result.node_updates;
  j["node_updates_full_model"] = result.node_updates_full_model;
  j["wall_time_s"] = result.wall_time_s;
  // Everything the run cost the library, the mesh choice included: what a caller pays per run.
  j["mesh_choice_time_s"] = scene.simulation.mesh_choice_time_s;
  j["run_time_s"] = scene.simulation.mesh_choice_time_s + result.call_time_s;
  j["energy_error"] = result.energy_error;
  j["max_penetration_m"] = result.max_penetration_m;
  j["stable"] = result.stable;
  if (!result.stable) j["failure"] = result.failure;
  j["warnings"] = result.warnings;
  if (const auto t = scene.simulation.tolerance) {  // the meshes chosen for it are in "bars"
    const double predicted = predict_gauge_error(scene, result.discretization).total;
    j["tolerance"] = *t;
    j["tolerance_is_default"] = scene.simulation.tolerance_is_default;
    j["predicted_gauge_error"] = predicted;
  } else if (!scene.simulation.tolerance_withheld.empty()) {
    j["tolerance_withheld"] = scene.simulation.tolerance_withheld;
  }
  return j;
}

}  // namespace shpb
