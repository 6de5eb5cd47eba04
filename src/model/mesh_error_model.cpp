#include "model/mesh_error_model.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <numeric>
#include <optional>

#include "core/error.hpp"
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

// Searches in the element transit stop at this ratio of their bounds (0.5 %: an element count
// within one element of the boundary for bars of up to 200 elements).
constexpr double kSearchRatio = 1.005;
// The scan from the coarsest transit: fine enough to find the first mesh meeting the target (the
// predicted error changes by a few % per step), coarse enough to take about 200 steps over 10⁷.
constexpr double kScanRatio = 1.08;

bool is_specimen(const Scene& scene, std::size_t i) {
  return scene.specimen && *scene.specimen == i;
}

// Courant numbers a tolerance may choose among: the default, and one closer to the exact C = 1
// (§1: no dispersion), where fronts are carried sharper and a coarser mesh meets the same error.
// Close to 1 the asynchronous rigid link between two bars whose steps differ by less than the
// margin 1 − C goes unstable (measured on the LANL PMMA bars, striker and incident steps 0.05–0.12
// % apart: unstable at C = 0.999 and 0.9999, stable at 0.995 for every ratio tried), so there the
// bars are meshed to step together (common_transit_s). C = 1 itself is marginal (a double root at
// the highest mode: energy error 0.75 on the PMMA test at 2 x bars against 1.1e-3 at 0.9999).
constexpr double kNearExactCourant = 0.9999;

// The finest division of the common transit tried near C = 1 (a 2 m bar with a 100 mm common
// divisor: 0.1 mm elements).
constexpr long kMaxCommonDivisions = 1000;

// Lengths are compared in whole micrometres when their common divisor is sought.
constexpr double kLengthQuantum = 1e-6;

// With every bar but the specimen elastic and meshed by the tolerance, all of one wave speed,
// and every interface a localized bipenalty link or bonded (the penalty methods' stability
// depends on C, §2), and no Courant number in the scene: the largest transit T that every bar's
// L/c is a whole multiple of (the lengths' greatest common divisor over c). Meshed at element
// transits T/k, those bars step together at any C. None otherwise.
std::optional<double> common_transit_s(const Scene& scene, const std::vector<bool>& free) {
  if (scene.simulation.courant) return std::nullopt;
  for (std::size_t k = 0; k + 1 < scene.bars.size(); ++k) {
    const ContactMethod m = interface_method(scene.contact, k);
    if (m != ContactMethod::kLocalizedBipenalty && m != ContactMethod::kBonded) return std::nullopt;
  }
  long long divisor = 0;
  double speed = 0;
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    if (is_specimen(scene, i)) continue;
    const BarSpec& b = scene.bars[i];
    if (!free[i] || !b.material.is_elastic()) return std::nullopt;
    const double c = b.material.wave_speed_m_s();
    if (speed > 0 && std::abs(c / speed - 1) > 1e-12) return std::nullopt;
    speed = c;
    const double units = b.length_m / kLengthQuantum;
    if (std::abs(units - std::round(units)) > 1e-6 * units) return std::nullopt;
    divisor = std::gcd(divisor, static_cast<long long>(std::llround(units)));
  }
  if (divisor == 0) return std::nullopt;
  return static_cast<double>(divisor) * kLengthQuantum / speed;
}

// A compliant link (an interface's `rise_time` τ) is carried by its bars' steps: measured on the
// LANL copper test (2 µs rise, C = 0.995), the energy error grows with the bars' step over τ —
// 2.2·10⁻³ at 0.45, 3.6·10⁻³ at 0.62–0.69, 6·10⁻³ at 0.87, 8·10⁻³ at 1.2 (a rigid link at the
// last meshes: 1·10⁻³) — so a tolerance meshes the bars at an element transit of at most half the
// shortest rise time (docs/methods.md §1.1), inside the measured region within 0.5 %.
constexpr double kRiseTimeTransits = 2;

// The coarsest element transit h/c the bars may take: the longest bar's, or kRiseTimeTransits per
// the shortest rise time of a compliant link.
double coarsest_transit_s(const Scene& scene) {
  double coarsest = longest_transit_s(scene);
  for (std::size_t k = 0; k + 1 < scene.bars.size(); ++k)
    if (const auto tau = interface_penalty(scene.contact, k).rise_time_s)
      coarsest = std::min(coarsest, *tau / kRiseTimeTransits);
  return coarsest;
}

// Meshes are chosen for a predicted error of this fraction of the tolerance: the model's scatter
// over its calibration runs is a factor 1.5 (rms of the log 0.41, kMeshErrorConstants).
constexpr double kTargetFraction = 0.65;

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

// Points of the frequency integral, up to where the record's Gaussian has fallen to e^{−60}.
constexpr int kFrequencyPoints = 800;
constexpr double kFrequencyEnd = 7.75;  // × 1/Δs: e^{−ω²Δs²} = e^{−60} there

// The record is a point sample every Δs: what a front carries above the Nyquist frequency π/Δs
// folds back onto the record's band. Averaged over where the samples fall on the front, the
// images at ω − 2πm/Δs add in energy, seen through the record's Gaussian:
//   (1/π) ∫₀^{ω_c} W(ω)/(1 + ω²τ²)/ω² dω,   W(ω) = Σ_{m≠0} e^{−(ω − 2πm/Δs)² Δs²},
// ω_c the lowest cut-off of the bars on the path (none of a reference recorded through the
// Gaussian, study/reference.hpp). The images beyond kAliasImages sample frequencies are left out
// (their share falls as 1/m²).
constexpr int kAliasImages = 16;
constexpr double kAliasStep = 0.1;  // × 1/Δs: 7 points per standard deviation of the Gaussian

double aliased_error_s(const ChainDiscretization& d, const std::vector<double>& x, double sample_s,
                       double rise_s) {
  double cutoff = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i] > 0)
      cutoff =
          std::min(cutoff, 2 * std::asin(std::min(d.bars[i].courant, 1.0)) / d.bars[i].time_step_s);
  const double images = 2 * M_PI / sample_s;
  const double top = std::min(cutoff, (kAliasImages + 0.5) * images);
  const double dw = kAliasStep / sample_s;
  double sum = 0;
  for (double w = 0.5 * M_PI / sample_s; w < top; w += dw) {
    const double m = std::max(1.0, std::round(w / images));  // the nearest image dominates
    double weight = 0;
    for (double k = std::max(1.0, m - 1); k <= m + 1; ++k)
      weight += std::exp(-std::pow((w - k * images) * sample_s, 2));
    sum += weight / (w * w * (1 + w * w * rise_s * rise_s));
  }
  return sum * dw / M_PI;
}

// (1/π) ∫ e^{−ω²Δs²}/(1 + ω²τ²) |H − 1|²/ω² dω for the bars' paths x (the model's I / A²).
// sin(z)/z, 1 at 0.
double sinc(double z) { return std::abs(z) < 1e-8 ? 1.0 : std::sin(z) / z; }

double front_error_s(const ChainDiscretization& d, const std::vector<double>& x,
                     std::size_t gauge_bar, double gauge_w, double sample_s, double rise_s,
                     double aliasing) {
  const double top = kFrequencyEnd / sample_s, dw = top / kFrequencyPoints;
  const BarDiscretization& g = d.bars[gauge_bar];
  double sum = 0;
  for (int j = 1; j <= kFrequencyPoints; ++j) {
    const double w = j * dw;
    double phase = 0, kg = 0;
    bool carried = true;
    for (std::size_t i = 0; i < x.size() && carried; ++i) {
      if (!(x[i] > 0) && i != gauge_bar) continue;
      const BarDiscretization& b = d.bars[i];
      const double half = 0.5 * w * b.time_step_s;
      const double s = half < 0.5 * M_PI ? std::sin(half) / b.courant : 2;
      if (s >= 1) {
        carried = false;  // above the mesh's cut-off: the frequency never reaches the gauge
        break;
      }
      const double k = 2 / b.element_length_m * std::asin(s);
      phase += x[i] * (k - w / b.wave_speed_m_s);
      if (i == gauge_bar) kg = k;
    }
    // The gauge reads element strains (each the mean over its element: sinc(κh/2)) interpolated
    // linearly between the centres around it, at fraction w of the pitch: the centres' values
    // lead and lag the gauge's own by w·h and (1 − w)·h, so
    //   F = sinc(κh/2) ((1 − w) e^{iκwh} + w e^{−iκ(1−w)h})   (at C = 1 exactly what is left).
    double miss = 1;
    if (carried) {
      const double kh = kg * g.element_length_m;
      const std::complex<double> f =
          sinc(0.5 * kh) * ((1 - gauge_w) * std::polar(1.0, kh * gauge_w) +
                            gauge_w * std::polar(1.0, -kh * (1 - gauge_w)));
      miss = std::norm(f * std::polar(1.0, phase) - 1.0);
    }
    const double weight = std::exp(-w * w * sample_s * sample_s) / (1 + w * w * rise_s * rise_s);
    sum += (j == kFrequencyPoints ? 0.5 : 1) * weight * miss / (w * w);
  }
  return sum * dw / M_PI +
         (aliasing > 0 ? aliasing * aliased_error_s(d, x, sample_s, rise_s) : 0.0);
}

}  // namespace

namespace {

// The bars' share by bar meshes and steps. The specimen is on no pulse's path in the
// model, so a search over specimen meshes finds the bars' share here instead of re-integrating it.
using BarsErrorCache = std::map<std::vector<double>, double>;

GaugeErrorPrediction predict(const Scene& scene, const ChainDiscretization& d,
                             const MeshErrorConstants& k, BarsErrorCache* cache) {
  GaugeErrorPrediction p;
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
  std::vector<double> key;  // what the bars' share depends on: each bar's mesh and step
  for (std::size_t i = 0; i < d.bars.size(); ++i)
    if (!is_specimen(scene, i))
      key.insert(key.end(), {1.0 * d.bars[i].elements, d.bars[i].time_step_s});
  if (const auto hit = cache ? cache->find(key) : BarsErrorCache::iterator{};
      cache && hit != cache->end()) {
    p.bars = hit->second;
  } else {
    double sum = 0;
    int gauges = 0;
    for (std::size_t b = *striker + 1; b < scene.bars.size(); ++b)
      for (const GaugeSpec& g : scene.bars[b].gauges) {
        // The gauge's place between the element centres around it, a fraction of their pitch.
        const double pitch = g.position_m / d.bars[b].element_length_m - 0.5;
        const double w = std::clamp(pitch - std::floor(pitch), 0.0, 1.0);
        sum += front_error_s(d, path_lengths(scene, *striker, b, g.position_m), b, w, sample_s,
                             p.rise_time_s, aliasing);
        ++gauges;
      }
    p.bars = gauges > 0 ? std::sqrt(k.front * 2 * sum / gauges / p.pulse_s) : 0.0;
    if (cache) (*cache)[key] = p.bars;
  }
  const auto resolution = [&](std::size_t i) {
    const BarDiscretization& b = d.bars[i];
    return k.specimen *
           std::pow(b.element_length_m / b.wave_speed_m_s / sample_s, k.specimen_order);
  };
  if (scene.specimen) p.specimen = resolution(*scene.specimen);
  double others = 0;  // Σ e_law² of the other material-law bars (pulse shapers)
  for (std::size_t i = 0; i < scene.bars.size(); ++i)
    if (!is_specimen(scene, i) && !scene.bars[i].material.is_elastic()) {
      const double e = resolution(i);
      others += e * e;
    }
  p.total = others > 0 ? std::sqrt(p.bars * p.bars + p.specimen * p.specimen + others)
                       : std::hypot(p.bars, p.specimen);
  return p;
}

}  // namespace

GaugeErrorPrediction predict_gauge_error(const Scene& scene, const ChainDiscretization& d,
                                         const MeshErrorConstants& k) {
  return predict(scene, d, k, nullptr);
}

namespace {

// Node updates of the scene as meshed, or infinity where discretize() refuses it (too large).
double cost(const Scene& scene, ChainDiscretization* d) {
  try {
    *d = discretize(scene);
    return d->node_updates_estimate;
  } catch (const InputError&) {
    return std::numeric_limits<double>::infinity();
  }
}

// The bars (not the specimen, not meshed by the user) at element transit δ = h/c.
void mesh_bars(Scene& scene, const std::vector<bool>& free, double delta) {
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    if (!free[i] || is_specimen(scene, i)) continue;
    BarSpec& b = scene.bars[i];
    const double n = std::ceil(b.length_m / (b.material.wave_speed_m_s() * delta) - 1e-9);
    b.elements = static_cast<int>(std::clamp(n, 1.0, 1e9));
  }
}

}  // namespace

GaugeErrorPrediction choose_meshes(Scene& scene) {
  const double asked = scene.simulation.tolerance.value_or(0);
  std::vector<bool> free(scene.bars.size());
  for (std::size_t i = 0; i < scene.bars.size(); ++i) free[i] = scene.bars[i].elements == 0;
  const auto striker = striker_bar(scene);
  if (!striker) return predict_gauge_error(scene, discretize(scene));  // NaN: nothing to predict

  // Specimen element counts tried (a geometric ladder), or the user's.
  std::vector<int> specimen_counts = {0};
  if (scene.specimen && free[*scene.specimen]) {
    specimen_counts.clear();
    for (double n = 4; n <= 4000; n *= 1.15) specimen_counts.push_back(static_cast<int>(n));
  }
  // Close to C = 1 only where the bars can step together (common_transit_s).
  const std::optional<double> common = common_transit_s(scene, free);
  // Element transits h/c tried for the bars: from one element per bar (at most half a compliant
  // link's rise time, kRiseTimeTransits) down to 1e-7 of the longest bar's.
  const double coarsest = coarsest_transit_s(scene), finest = longest_transit_s(scene) * 1e-7;

  BarsErrorCache cache;
  double closest = std::numeric_limits<double>::infinity();  // when none meets the tolerance
  Scene most_accurate = scene;
  // The cheapest mesh predicted at most `target` into `best`; false if there is none.
  const auto cheapest = [&](double target, Scene& best) {
    double best_cost = std::numeric_limits<double>::infinity();
    for (int ns : specimen_counts) {
      Scene s = scene;
      if (ns > 0) s.bars[*scene.specimen].elements = ns;
      ChainDiscretization d;
      const auto affordable = [&](double delta) {
        mesh_bars(s, free, delta);
        return std::isfinite(cost(s, &d));
      };
      const auto error_at = [&](double delta) {
        return affordable(delta) ? predict(s, d, kMeshErrorConstants, &cache).total
                                 : std::numeric_limits<double>::infinity();
      };
      // The finest affordable element transit (refusal by discretize() is monotone in δ)…
      double fine = finest;
      if (!affordable(fine)) {
        if (!affordable(coarsest)) continue;
        double a = finest, b = coarsest;
        while (b / a > kSearchRatio) {
          const double mid = std::sqrt(a * b);
          (affordable(mid) ? b : a) = mid;
        }
        fine = b;
      }
      // … then from the coarsest transit down, a step of kScanRatio at a time, to the first that
      // meets the target, and bisection back to its coarser neighbour: the error is not monotone
      // in δ (the fronts' dispersion falls with it, their aliasing in the record grows).
      double lo = coarsest, hi = coarsest, e = error_at(lo);
      Scene closest_here = s;
      double closest_e = e;
      while (!(e <= target) && lo > fine) {
        hi = lo;
        lo = std::max(fine, lo / kScanRatio);
        e = error_at(lo);
        if (e < closest_e) closest_e = e, closest_here = s;
      }
      if (!(e <= target) && closest_e < closest) closest = closest_e, most_accurate = closest_here;
      if (e <= target) {
        while (hi / lo > kSearchRatio) {
          const double mid = std::sqrt(lo * hi);
          (error_at(mid) <= target ? lo : hi) = mid;
        }
        error_at(lo);
        if (d.node_updates_estimate < best_cost) best_cost = d.node_updates_estimate, best = s;
      }
      if (common) {
        // Near C = 1: the bars at transits T/k, k = 1, 2, … up to the first that meets the target.
        Scene near = s;
        near.simulation.courant = kNearExactCourant;
        ChainDiscretization dn;
        for (long k = 1; k <= kMaxCommonDivisions; ++k) {
          if (*common / k > coarsest) continue;  // coarser than a compliant link allows
          mesh_bars(near, free, *common / k);
          if (!std::isfinite(cost(near, &dn))) break;
          if (dn.node_updates_estimate >= best_cost) break;  // finer only costs more
          const GaugeErrorPrediction p = predict(near, dn, kMeshErrorConstants, &cache);
          if (!(p.specimen <= target)) break;  // the specimen's share alone is too much
          if (p.total <= target) {
            best_cost = dn.node_updates_estimate, best = near;
            break;
          }
        }
      }
    }
    return std::isfinite(best_cost);
  };
  // With the margin of the model's scatter if any mesh allows it; else (the bars the user meshed,
  // or the record's aliasing of sharp fronts, leave no room for it) halfway between the best
  // predicted error and the tolerance; else the most accurate mesh (refused by resolve_scene()).
  Scene best = scene;
  if (cheapest(kTargetFraction * asked, best) ||
      (closest <= asked && cheapest(0.5 * (closest + asked), best)))
    scene = best;
  else if (std::isfinite(closest))
    scene = most_accurate;
  return predict_gauge_error(scene, discretize(scene));
}

}  // namespace shpb
