#include "model/mesh_error_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>

#include "core/error.hpp"
#include "model/front_error.hpp"
#include "model/mesh_error_search.hpp"
#include "model/wave_travel.hpp"

namespace shpb {

// Measured by tools/calibrate_tolerance.cpp (its header gives the command) on the striker-on-bar,
// classic, LANL copper and LANL PMMA experiments against references seen as a record sees them,
// 37 runs from 1/4 to 2 x the automatic bar meshes, Courant 0.5–0.995, specimens of 4 elements to
// 2 x: measured/predicted within a factor 3.5 (rms of the log 0.34; the worst, 0.63 % measured for
// 0.18 % predicted, is the LANL copper test's floor, reached from 1 x whatever the mesh). The
// theory alone (front = 1) predicts the striker-on-bar's exact solution within 8 % at 1/4–4 x.
const MeshErrorConstants kMeshErrorConstants = {1.12, 0.0174, 1.0};

namespace {

// Distances the pulses a gauge records travel in each bar before it has recorded them: the
// striker's release wave runs 2 L_s (the pulse's tail; its front none: L_s on average); a bar
// between the impact and the gauge is crossed whole, twice left of the specimen (the reflected
// pulse); on the gauge's own bar the pulse runs to the gauge and, left of the specimen, on to the
// specimen face and back. The specimen is left out (its own term).
std::vector<double> path_lengths(const Scene& scene, std::size_t striker, std::size_t bar,
                                 double position) {
  std::vector<double> x(scene.bars.size(), 0.0);
  const bool incident_side = scene.specimen && bar < *scene.specimen;
  x[striker] = scene.bars[striker].length_m;
  for (std::size_t i = striker + 1; i < bar; ++i)
    x[i] = scene.bars[i].length_m * (incident_side ? 2 : 1);
  x[bar] = incident_side ? 2 * scene.bars[bar].length_m - position : position;
  if (scene.specimen) x[*scene.specimen] = 0;
  return x;
}

// At most this many later passes of the pulses over a gauge are counted (a record of ten round
// trips in its bar: 5 ms on a 0.5 m steel bar); the model's cost grows with each.
constexpr int kMaxLaterPasses = 20;

// A pass of the recorded pulses over a gauge: the distances its fronts have travelled in each bar,
// how many of its two fronts the record holds and how long it lasts in the record.
struct Pass {
  std::vector<double> x;
  double fronts = 2, recorded_s = 0;
};

// The passes a record of `duration_s` holds after the pulses path_lengths() counts (the incident
// and, left of the specimen, the reflected pulse): those pulses bounce between the ends of the
// gauge's bar (a free end, the specimen's face), passing the gauge again every round trip to the
// end they run to — the reflected pulse off the struck end, the transmitted pulse off the far end —
// each time dispersed over a longer path (docs/methods.md §1.1, "Later passes"). None on any
// experiment: their records end before.
std::vector<Pass> later_passes(const Scene& scene, std::size_t striker, std::size_t bar,
                               double position, double duration_s) {
  const double c = scene.bars[bar].material.wave_speed_m_s(), length = scene.bars[bar].length_m;
  const double pulse = striker_pulse_s(scene, striker);
  double t = pulses_passed_s(scene, striker, bar, position) - pulse;  // the last front's arrival
  bool leftwards = scene.specimen && bar < *scene.specimen;  // the reflected pulse runs left
  Pass pass{path_lengths(scene, striker, bar, position)};
  std::vector<Pass> passes;
  for (int k = 0; k < kMaxLaterPasses; ++k) {
    const double leg = 2 * (leftwards ? position : length - position);
    t += leg / c;
    pass.x[bar] += leg;
    leftwards = !leftwards;
    if (!(t < duration_s)) break;
    pass.fronts = t + pulse < duration_s ? 2 : 1;
    pass.recorded_s = std::min(pulse, duration_s - t);
    passes.push_back(pass);
  }
  return passes;
}

// The share of its norm the record of a gauge left of the specimen keeps where the reflected pulse
// reaches it before the incident one has passed (overlap o of the pulse T_p: the gauge closer to
// the specimen than half the pulse, which validate warns of). Of opposite sign (a specimen of lower
// impedance), the two cancel over the overlap, while their fronts stay whole: with the reflection
// coefficient r of the specimen's face, the record's norm A²[(T_p − o)(1 + r²) + o(1 + r)²] against
// the A²T_p(1 + r²) of two pulses apart. r from the elastic impedances ρcA of the specimen and the
// gauge's bar; a specimen that flows reflects less than that r says (it carries its flow stress:
// the classic set-up's reflected pulse 0.67 of the incident, r −0.83), so the share is taken no
// larger than it is. 1 without a specimen, right of it or without an overlap of more than a sample
// interval.
double overlap_norm_share(const Scene& scene, std::size_t striker, std::size_t bar,
                          double position) {
  if (!scene.specimen || bar >= *scene.specimen) return 1;
  const double pulse = striker_pulse_s(scene, striker);
  const double overlap = pulse - 2 * travel_time_s(scene, bar, position, *scene.specimen, 0);
  if (!(overlap > 1 / scene.simulation.sample_rate_Hz)) return 1;  // none the record resolves
  const double zs = scene.bars[*scene.specimen].impedance_kg_s(),
               zb = scene.bars[bar].impedance_kg_s();
  const double r = (zs - zb) / (zs + zb);
  return 1 + 2 * r * overlap / ((1 + r * r) * pulse);
}

}  // namespace

bool faces_weighed_more(const Scene& scene) {
  const auto striker = striker_bar(scene);
  if (!striker || !scene.specimen) return false;
  const double duration_s = run_duration_s(scene);
  for (std::size_t b = *striker + 1; b < scene.bars.size(); ++b)
    for (const GaugeSpec& g : scene.bars[b].gauges)
      if (!later_passes(scene, *striker, b, g.position_m, duration_s).empty() ||
          overlap_norm_share(scene, *striker, b, g.position_m) < 1)
        return true;
  return false;
}

namespace {

// The path of the fronts a gauge at `position` on `bar` records, the chain meshed as `d`: the
// bars crossed (distances x) and the gauge's own, and the gauge's place between the element
// centres around it (a fraction of the pitch).
FrontPath front_path(const ChainDiscretization& d, const std::vector<double>& x, std::size_t bar,
                     double position, double aliasing) {
  FrontPath p;
  p.aliasing = aliasing;
  const double pitch = position / d.bars[bar].element_length_m - 0.5;
  p.gauge_w = std::clamp(pitch - std::floor(pitch), 0.0, 1.0);
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i] > 0 || i == bar) {
      const BarDiscretization& b = d.bars[i];
      p.bars.push_back(
          {x[i], b.courant, b.element_length_m, b.wave_speed_m_s, b.time_step_s, i == bar});
    }
  return p;
}

}  // namespace

double combined_error(double bars, double specimen, double others) {
  return others > 0 ? std::sqrt(bars * bars + specimen * specimen + others)
                    : std::hypot(bars, specimen);
}

double law_bar_share(const BarDiscretization& b, double sample_s, const MeshErrorConstants& k) {
  return k.specimen * std::pow(b.element_length_m / b.wave_speed_m_s / sample_s, k.specimen_order);
}

double other_law_bars(const Scene& scene, const ChainDiscretization& d, double sample_s,
                      const MeshErrorConstants& k) {
  double others = 0;
  for (std::size_t i = 0; i < scene.bars.size(); ++i)
    if (!is_specimen(scene, i) && !scene.bars[i].material.is_elastic()) {
      const double e = law_bar_share(d.bars[i], sample_s, k);
      others += e * e;
    }
  return others;
}

namespace {

// A path whose fronts a gauge records, weighed by its share of the gauges' recorded norm.
struct Gauge {
  FrontPath path;
  double weight = 1;
};

// Every gauge's paths: the pulses path_lengths() counts, one pulse (two fronts, norm A² T_p) per
// gauge as the model was calibrated, and the later passes its record holds (later_passes()), each
// counted by the fronts recorded and its norm by the time recorded, the first pulse's norm by the
// share overlap_norm_share() leaves. Weighed so that the sum of weight × I over them, in the bars'
// share √(front · 2 Σ / (gauges T_p)), averages the gauges' fronts' error over their norms: every
// weight is 1 where no later pass is recorded and no pulses overlap.
std::vector<Gauge> gauge_paths(const Scene& scene, const ChainDiscretization& d,
                               std::size_t striker, double aliasing) {
  const double duration_s = run_duration_s(scene);
  const double pulse = striker_pulse_s(scene, striker);
  std::vector<Gauge> path;
  for (std::size_t b = striker + 1; b < scene.bars.size(); ++b)
    for (const GaugeSpec& g : scene.bars[b].gauges) {
      const std::size_t first = path.size();
      const std::vector<double> x = path_lengths(scene, striker, b, g.position_m);
      path.push_back({front_path(d, x, b, g.position_m, aliasing), 1.0});
      double norm = overlap_norm_share(scene, striker, b, g.position_m);  // in A² T_p
      for (const Pass& p : later_passes(scene, striker, b, g.position_m, duration_s)) {
        path.push_back({front_path(d, p.x, b, g.position_m, aliasing), p.fronts / 2});
        norm += p.recorded_s / pulse;
      }
      for (std::size_t j = first; j < path.size(); ++j) path[j].weight /= norm;
    }
  return path;
}

}  // namespace

Predicted predict(const Scene& scene, const ChainDiscretization& d, const MeshErrorConstants& k,
                  SearchCache* cache, PredictMode mode) {
  Predicted p;
  const auto striker = striker_bar(scene);
  if (!striker) {
    p.total = p.bars = std::numeric_limits<double>::quiet_NaN();
    return p;
  }
  p.pulse_s = striker_pulse_s(scene, *striker);
  p.rise_time_s = interface_penalty(scene.contact, *striker).rise_time_s.value_or(0.0);
  const double sample_s = 1 / d.sample_rate_Hz;
  // A record filtered before it is sampled has no aliasing (model/scene.hpp gauges_filtered).
  const double aliasing = gauges_filtered(scene.simulation) ? 0.0 : k.aliasing;
  SearchCache local;
  SearchCache& c = cache ? *cache : local;
  if (!c.weights || c.weights->sample_s != sample_s || c.weights->rise_s != p.rise_time_s) {
    c.weights = frequency_weights(sample_s, p.rise_time_s);
    c.bars.clear();
  }
  const FrequencyWeights& f = *c.weights;

  if (scene.specimen) p.specimen = law_bar_share(d.bars[*scene.specimen], sample_s, k);
  const double others = other_law_bars(scene, d, sample_s, k);
  const auto total = [&](double bars) { return combined_error(bars, p.specimen, others); };
  std::vector<double> key;  // what the bars' share depends on: each bar's mesh and step
  for (std::size_t i = 0; i < d.bars.size(); ++i)
    if (!is_specimen(scene, i))
      key.insert(key.end(), {1.0 * d.bars[i].elements, d.bars[i].time_step_s});
  // The gauges: their paths, their place between the element centres around them (a fraction
  // of the pitch).
  int gauges = 0;
  for (std::size_t b = *striker + 1; b < scene.bars.size(); ++b)
    gauges += static_cast<int>(scene.bars[b].gauges.size());
  const auto share = [&](double sum) {
    return gauges > 0 ? std::sqrt(k.front * 2 * sum / gauges / p.pulse_s) : 0.0;
  };
  // Told to stop where the mesh misses `above`: the sum of the gauges' integrals that misses it
  // with this specimen, and the one that misses it whatever the specimen (the bound misses by the
  // rounding of its sum at most: a margin of 10⁻⁹).
  const double above = mode.above * (1 + 1e-9);
  const double scale = gauges * p.pulse_s / (2 * k.front);
  const double misses_alone = std::isfinite(mode.above) ? (above * above - others) * scale
                                                        : std::numeric_limits<double>::infinity();
  const double misses = !std::isfinite(mode.above) ? std::numeric_limits<double>::infinity()
                        : mode.bars_alone
                            ? misses_alone
                            : (above * above - p.specimen * p.specimen - others) * scale;
  auto hit = c.bars.find(key);
  if (hit == c.bars.end() || (!hit->second.exact && !(hit->second.sum > misses))) {
    const std::vector<Gauge> path = gauge_paths(scene, d, *striker, aliasing);
    // First against the bounds, then integrating and stopping where the sum so far passes the
    // sum that misses whatever the specimen.
    SearchCache::Bars found{0.0, false};
    double sum = 0;
    std::vector<double> floors(path.size());
    bool missed = false;
    if (std::isfinite(misses)) {
      for (std::size_t j = 0; j < path.size(); ++j)
        sum += floors[j] = path[j].weight * front_error_floor_s(path[j].path, f);
      if (sum > misses) found.sum = sum, missed = true;
    }
    if (!missed) {
      double full = 0;
      found.exact = true;
      for (std::size_t j = 0; j < path.size(); ++j) {
        const Gauge& g = path[j];
        bool gave_up = false;
        const double i =
            g.weight * front_error_s(g.path, f, (misses_alone - sum) / g.weight, &gave_up);
        if (gave_up) {  // this gauge's part so far, the others' bounds
          found = {sum + i, false};
          break;
        }
        sum += i - floors[j];
        full += i;
      }
      if (found.exact) found.sum = full;
    }
    // A bound shows a miss for this specimen only: kept where it holds for every one.
    if (found.exact || found.sum > misses_alone) c.bars[key] = found;
    p.bars = share(found.sum);
    p.bars_exact = found.exact;
  } else {
    p.bars = share(hit->second.sum);
    p.bars_exact = hit->second.exact;
  }
  p.total = total(p.bars);
  return p;
}

GaugeErrorPrediction predict_gauge_error(const Scene& scene, const ChainDiscretization& d,
                                         const MeshErrorConstants& k) {
  return predict(scene, d, k, nullptr);
}

}  // namespace shpb
