#include "model/discretization.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "core/error.hpp"
#include "core/json_value.hpp"
#include "model/wave_travel.hpp"

namespace shpb {

namespace {
// Margin on the default duration so the tail of the last pulse is recorded whole.
constexpr double kDurationMargin = 1.1;

// In double: a kilometre-long bar would overflow an int before the resource check sees it.
double automatic_elements(const Scene& scene, std::size_t i) {
  const BarSpec& bar = scene.bars[i];
  if (bar.elements > 0) return bar.elements;
  const bool specimen = scene.specimen && *scene.specimen == i;
  const double h = specimen ? kSpecimenElementLength_m : kBarElementLength_m;
  const int minimum = specimen ? kMinSpecimenElements : kMinBarElements;
  return std::max<double>(minimum, std::ceil(bar.length_m / h - 1e-9));
}

// Refuses a set-up that cannot run here before anything is allocated, naming the entry
// that drives the cost with the estimated memory and time. Estimates, checked against the
// measured peak (tests/robustness/test_estimates.cpp): per element the bar state (7 doubles) and
// one material point (~15 doubles); per recorded sample every full-rate column twice (the
// recorder's buffer and the result handed to the writers) and one time column per series
// (gauges, interfaces, specimen); the field grid and the energy record are small and fixed, in
// kProcessBytes with the program itself.
constexpr double kBytesPerElement = 200;
constexpr double kProcessBytes = 8e6;
constexpr double kMaxMemoryBytes = 4e9;        // beyond a lab workstation's spare memory
constexpr double kNodeUpdatesPerSecond = 5e7;  // measured order in Release on one core
constexpr double kMaxNodeUpdates = 1e12;       // ~6 hours at that rate

std::string gigabytes(double bytes) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g GB", bytes / 1e9);
  return b;
}

std::string duration_text(double seconds) {
  char b[64];
  if (seconds < 120)
    std::snprintf(b, sizeof b, "%.2g s", seconds);
  else if (seconds < 7200)
    std::snprintf(b, sizeof b, "%.2g min", seconds / 60);
  else if (seconds < 2 * 86400 * 365.0)
    std::snprintf(b, sizeof b, "%.2g h", seconds / 3600);
  else
    std::snprintf(b, sizeof b, "%.2g years", seconds / (86400 * 365.0));
  return b;
}

// What each bar costs over the run (free flight included), in doubles before any count is cast
// to an integer: its elements and its steps (at global steps the smallest step's count).
struct BarCost {
  double elements = 0, run_steps = 0;
};
// Bar i's own stable step with `elements` elements (before global stepping takes the smallest).
double own_step_s(const Scene& scene, std::size_t i, double elements, double courant) {
  return bar_courant(scene, i, courant) * scene.bars[i].length_m / elements /
         scene.bars[i].material.wave_speed_m_s();
}

std::vector<BarCost> bar_costs(const Scene& scene, double run_s, double courant) {
  std::vector<BarCost> costs;
  costs.reserve(scene.bars.size());
  double global_dt = 0;
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    const double elements = automatic_elements(scene, i);
    const double dt = own_step_s(scene, i, elements, courant);
    costs.push_back({elements, std::ceil(run_s / dt)});
    global_dt = i == 0 ? dt : std::min(global_dt, dt);
  }
  if (scene.simulation.stepping == Stepping::kGlobal)
    for (BarCost& c : costs) c.run_steps = std::ceil(run_s / global_dt);
  return costs;
}

// The recorded series' bytes: every full-rate column twice (the recorder's buffer and the result
// handed to the writers) and one time column per series (gauges, interfaces, specimen).
double record_bytes(const Scene& scene, double recorded_s) {
  std::size_t gauges = 0;
  for (const BarSpec& b : scene.bars) gauges += b.gauges.size();
  const double interfaces = static_cast<double>(scene.bars.size()) - 1;
  const double specimen = scene.specimen ? 1 : 0;
  const double columns = static_cast<double>(gauges) + 2 * interfaces + 5 * specimen;
  const double series = (gauges > 0 ? 1 : 0) + (interfaces > 0 ? 1 : 0) + specimen;
  return 8 * (2 * columns + series) * recorded_s * scene.simulation.sample_rate_Hz;
}

// The chain's estimates from its bars' costs and its record: one sum for discretize() and for a
// mesh search's re-pricing (estimates_with_bar()). `cost(i)` is bar i's BarCost.
struct Estimates {
  double mesh_bytes = 0, node_updates = 0;
};
template <class CostOf>
Estimates sum_estimates(std::size_t bars, CostOf cost, double records, ChainDiscretization& d) {
  Estimates e;
  for (std::size_t i = 0; i < bars; ++i) {
    const BarCost c = cost(i);
    e.mesh_bytes += kBytesPerElement * c.elements;
    e.node_updates += (c.elements + 1) * c.run_steps;
  }
  d.record_bytes_estimate = records;
  d.memory_estimate_bytes = kProcessBytes + e.mesh_bytes + records;
  d.node_updates_estimate = e.node_updates;
  return e;
}

// The bar whose own step, far below the others', alone puts the run beyond kMaxNodeUpdates: the
// run would be within it were that bar — or, a material being to blame, every bar of its material
// — to step as the next finest bar. `material`: the wave speed departs further from the next
// bar's than the element length does (a bar shorter than the fewest automatic elements, or its
// own elements, otherwise).
struct FinestStep {
  std::size_t bar = 0;
  bool material = false;
  double step_s = 0, next_step_s = 0;
};
std::optional<FinestStep> finest_step_to_blame(const Scene& scene,
                                               const std::vector<BarCost>& costs, double run_s,
                                               double courant) {
  std::vector<double> steps;
  for (std::size_t i = 0; i < costs.size(); ++i)
    steps.push_back(own_step_s(scene, i, costs[i].elements, courant));
  const auto finest =
      static_cast<std::size_t>(std::min_element(steps.begin(), steps.end()) - steps.begin());
  const std::string& material = scene.bars[finest].material.name;
  const bool global = scene.simulation.stepping == Stepping::kGlobal;
  for (const bool by_material : {false, true}) {
    const auto moved = [&](std::size_t i) {
      return by_material ? scene.bars[i].material.name == material : i == finest;
    };
    double next = std::numeric_limits<double>::infinity();
    std::size_t next_bar = finest;
    for (std::size_t i = 0; i < steps.size(); ++i)
      if (!moved(i) && steps[i] < next) next = steps[i], next_bar = i;
    if (!std::isfinite(next)) return std::nullopt;  // every bar moved: no other to step as
    double node_updates = 0;
    for (std::size_t i = 0; i < costs.size(); ++i)
      node_updates += (costs[i].elements + 1) * std::ceil(run_s / (global     ? next
                                                                   : moved(i) ? next
                                                                              : steps[i]));
    if (node_updates > kMaxNodeUpdates) continue;
    const BarSpec &f = scene.bars[finest], &n = scene.bars[next_bar];
    const double h = f.length_m / costs[finest].elements;
    const double h_next = n.length_m / costs[next_bar].elements;
    const bool wave_speed = f.material.wave_speed_m_s() / n.material.wave_speed_m_s() > h_next / h;
    return FinestStep{finest, by_material || wave_speed, steps[finest], next};
  }
  return std::nullopt;
}

// `run_s` includes the free flight before first contact; `recorded_s` is what is sampled.
void refuse_unaffordable(const Scene& scene, const std::vector<BarCost>& costs, double run_s,
                         double recorded_s, double courant, ChainDiscretization& estimate) {
  const double records = record_bytes(scene, recorded_s);
  const double mesh_bytes =
      sum_estimates(
          costs.size(), [&](std::size_t i) { return costs[i]; }, records, estimate)
          .mesh_bytes;
  if (affordable(estimate)) return;
  const double memory = estimate.memory_estimate_bytes;
  const double node_updates = estimate.node_updates_estimate;
  double biggest = 0;
  std::size_t largest = 0;
  for (std::size_t i = 0; i < costs.size(); ++i)
    if (costs[i].elements > biggest) biggest = costs[i].elements, largest = i;
  std::string where, value;
  const double flight = first_contact_delay_s(scene);
  if (flight > 0.5 * run_s && node_updates > kMaxNodeUpdates) {
    // The striker's free flight across a gap is most of the run.
    std::size_t k = 0;
    while (k + 1 < scene.bars.size() && !(scene.bars[k].gap_m > 0)) ++k;
    where = "bars[" + std::to_string(k) + "].gap";
    value = JsonValue::format(scene.bars[k].gap_m, Dimension::kLength);
  } else if (records > mesh_bytes && memory > kMaxMemoryBytes) {
    // The record is duration × sample rate: the sample rate is to blame when it samples finer
    // than the solver steps (samples between steps hold nothing new), else the duration.
    double most_steps = 0;
    for (const BarCost& c : costs) most_steps = std::max(most_steps, c.run_steps);
    const double finest_step_s = run_s / most_steps;
    const bool oversampled = scene.simulation.sample_rate_Hz * finest_step_s > 1;
    const bool duration = scene.simulation.duration_s && !oversampled;
    where = duration ? "simulation.duration" : "simulation.sample_rate";
    value = duration ? JsonValue::format(run_s, Dimension::kTime)
                     : JsonValue::format(scene.simulation.sample_rate_Hz, Dimension::kFrequency);
  } else if (const auto f = memory > kMaxMemoryBytes
                                ? std::nullopt
                                : finest_step_to_blame(scene, costs, run_s, courant)) {
    const BarSpec& bar = scene.bars[f->bar];
    const std::string at = "bars[" + std::to_string(f->bar) + "]";
    char b[400];
    std::snprintf(b, sizeof b,
                  "bar \"%s\" steps every %.3g s (elements of %.3g m, wave speed %.3g m/s), %.3g "
                  "times finer than the next bar: the run would need %.3g node updates (about %s "
                  "at %.0e node updates/s; limit %.0e): check its %s",
                  bar.name.c_str(), f->step_s, bar.length_m / costs[f->bar].elements,
                  bar.material.wave_speed_m_s(), f->next_step_s / f->step_s, node_updates,
                  duration_text(node_updates / kNodeUpdatesPerSecond).c_str(),
                  kNodeUpdatesPerSecond, kMaxNodeUpdates,
                  f->material ? "material's density and modulus" : "length and elements");
    if (f->material)
      throw input_error(scene.file.string(), at + ".material", "\"" + bar.material.name + "\"", b);
    if (bar.elements > 0)
      throw input_error(scene.file.string(), at + ".elements", std::to_string(bar.elements), b);
    throw input_error(scene.file.string(), at + ".length",
                      JsonValue::format(bar.length_m, Dimension::kLength), b);
  } else if (memory > kMaxMemoryBytes || !scene.simulation.duration_s) {
    const BarSpec& bar = scene.bars[largest];
    where = "bars[" + std::to_string(largest) + (bar.elements > 0 ? "].elements" : "].length");
    value = bar.elements > 0 ? std::to_string(bar.elements)
                             : JsonValue::format(bar.length_m, Dimension::kLength);
  } else {
    where = "simulation.duration";
    value = JsonValue::format(run_s, Dimension::kTime);
  }
  char b[400];
  std::snprintf(b, sizeof b,
                "the run would need about %s of memory and %.3g node updates (largest bar %.3g "
                "elements; about %s at %.0e node updates/s); refused before allocating (limits %s, "
                "%.0e node updates): use fewer elements, shorter bars, a shorter duration or a "
                "lower sample rate",
                gigabytes(memory).c_str(), node_updates, biggest,
                duration_text(node_updates / kNodeUpdatesPerSecond).c_str(), kNodeUpdatesPerSecond,
                gigabytes(kMaxMemoryBytes).c_str(), kMaxNodeUpdates);
  throw input_error(scene.file.string(), where, value, b);
}
}  // namespace

double bar_courant(const Scene& scene, std::size_t bar, double courant) {
  const BarSpec& b = scene.bars[bar];
  const bool specimen = scene.specimen && *scene.specimen == bar;
  if (b.material.is_elastic())
    return specimen ? std::min(courant, kElasticSpecimenCourant) : courant;
  const double e_max = scene.simulation.finite_strain
                           ? scene.simulation.max_strain.value_or(kDefaultMaxStrain)
                           : 0.0;
  // Face friction does not stiffen the elements: it acts at the faces (solver/bar_integrator.cpp).
  return courant * (1 - e_max);
}

double first_contact_delay_s(const Scene& scene) {
  double delay = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < scene.bars.size(); ++k) {
    const double closing = scene.bars[k].velocity_m_s - scene.bars[k + 1].velocity_m_s;
    if (closing > 0) delay = std::min(delay, scene.bars[k].gap_m / closing);
  }
  return std::isfinite(delay) ? delay : 0.0;
}

double default_duration_s(const Scene& scene) {
  if (scene.bars.empty()) return 0;
  if (const auto passed = pulses_passed_s(scene)) return *passed * kDurationMargin;
  return 2.0 * longest_transit_s(scene) * kDurationMargin;
}

double run_duration_s(const Scene& scene) {
  return scene.simulation.duration_s.value_or(default_duration_s(scene));
}

bool affordable(const ChainDiscretization& d) {
  return d.memory_estimate_bytes <= kMaxMemoryBytes && d.node_updates_estimate <= kMaxNodeUpdates;
}

ChainEstimates estimates_with_bar(const ChainDiscretization& d, std::size_t i,
                                  const BarDiscretization& b) {
  ChainDiscretization e;
  sum_estimates(
      d.bars.size(),
      [&](std::size_t k) {
        const BarDiscretization& bar = k == i ? b : d.bars[k];
        return BarCost{1.0 * bar.elements, bar.run_steps};
      },
      d.record_bytes_estimate, e);
  return {e.memory_estimate_bytes, e.node_updates_estimate, affordable(e)};
}

namespace {

// discretize() past its checks, into `d`: `costs` from bar_costs() (every count fits an int).
void plan_bars(const Scene& scene, double duration_s, double courant,
               const std::vector<BarCost>& costs, ChainDiscretization& d) {
  d.sample_rate_Hz = scene.simulation.sample_rate_Hz;
  d.stepping = scene.simulation.stepping;
  d.duration_s = duration_s;
  d.bars.reserve(scene.bars.size());
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    BarDiscretization b;
    b.elements = static_cast<int>(costs[i].elements);
    b.element_length_m = scene.bars[i].length_m / b.elements;
    // The stable step is fixed at the elastic bound for every material law (material_law.hpp),
    // for the shortest element finite strain allows (above): there the Courant number is the
    // scene's; the one reported is on the reference length.
    b.wave_speed_m_s = scene.bars[i].material.wave_speed_m_s();
    b.critical_step_s = b.element_length_m / b.wave_speed_m_s;
    b.time_step_s = bar_courant(scene, i, courant) * b.critical_step_s;
    b.courant = b.time_step_s / b.critical_step_s;  // on the reference length h
    b.run_steps = costs[i].run_steps;
    d.bars.push_back(b);
  }
  if (d.stepping == Stepping::kGlobal && !d.bars.empty()) {
    double dt = d.bars.front().time_step_s;
    for (const auto& b : d.bars) dt = std::min(dt, b.time_step_s);
    for (auto& b : d.bars) {
      b.time_step_s = dt;
      b.courant = dt / b.critical_step_s;
    }
  }
  for (auto& b : d.bars) b.steps = static_cast<long>(std::ceil(d.duration_s / b.time_step_s));
}

}  // namespace

ChainDiscretization discretize(const Scene& scene) {
  for (std::size_t i = 0; i < scene.bars.size(); ++i)
    if (!scene.bars[i].has_material)
      throw input_error(scene.file.string(), "bars[" + std::to_string(i) + "].material",
                        "(missing)",
                        "a simulation needs every bar's material (only `process` works without "
                        "the specimen's)");
  const double duration_s = run_duration_s(scene);
  const double courant = scene.simulation.courant.value_or(kDefaultCourant);
  const double run_s = duration_s + first_contact_delay_s(scene);  // free flight included
  const std::vector<BarCost> costs = bar_costs(scene, run_s, courant);
  ChainDiscretization d;
  refuse_unaffordable(scene, costs, run_s, duration_s, courant, d);
  plan_bars(scene, duration_s, courant, costs, d);
  return d;
}

ChainDiscretization plan_chain(const Scene& scene, double duration_s) {
  const double courant = scene.simulation.courant.value_or(kDefaultCourant);
  const std::vector<BarCost> costs =
      bar_costs(scene, duration_s + first_contact_delay_s(scene), courant);
  ChainDiscretization d;
  sum_estimates(
      costs.size(), [&](std::size_t i) { return costs[i]; }, record_bytes(scene, duration_s), d);
  plan_bars(scene, duration_s, courant, costs, d);
  return d;
}

}  // namespace shpb
