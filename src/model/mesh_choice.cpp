// The cheapest meshes the gauge error model predicts meet a tolerance (model/mesh_choice.hpp).
#include "model/mesh_choice.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>

#include "model/mesh_error_search.hpp"
#include "model/wave_travel.hpp"

namespace shpb {

namespace {

// Searches in the element transit stop at this ratio of their bounds (0.5 %: an element count
// within one element of the boundary for bars of up to 200 elements).
constexpr double kSearchRatio = 1.005;
// The scan from the coarsest transit: fine enough to find the first mesh meeting the target (the
// predicted error changes by a few % per step), coarse enough to take about 200 steps over 10⁷.
constexpr double kScanRatio = 1.08;

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

// Whatever the tolerance, a bar carries the loading pulse (its duration T_p = 2 L_s/c_s, the
// shortest wave the striker sends) over at least this many elements: the model weighs a front by
// its rise, so a long rise time (a soft link) counts a pulse as resolved at any mesh, down to one
// element per bar; ten elements leave a plateau of six between its two fronts, each spread over
// two elements by the gauge's interpolation (docs/methods.md §1.1).
constexpr double kElementsPerPulse = 10;

// The floor on the bars' element transit: T_p / kElementsPerPulse (none without a striker).
double pulse_floor_transit_s(const Scene& scene) {
  const auto striker = striker_bar(scene);
  return striker ? striker_pulse_s(scene, *striker) / kElementsPerPulse
                 : std::numeric_limits<double>::infinity();
}

// Meshes are chosen for a predicted error of this fraction of the tolerance: the model's scatter
// over its calibration runs is a factor 1.5 (rms of the log 0.41, kMeshErrorConstants).
constexpr double kTargetFraction = 0.65;

// The common transit of the bars meshed close to C = 1: only where they can step together
// (common_transit_s) and no record weighs the specimen's faces more than the calibration's,
// where the model's prediction there falls short (faces_weighed_more).
std::optional<double> near_exact_transit_s(const Scene& scene, const std::vector<bool>& free) {
  return faces_weighed_more(scene) ? std::nullopt : common_transit_s(scene, free);
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

// A candidate mesh as the search sees it: whether discretize() affords it, its node updates, and
// (error()) its predicted error or a bound showing it misses the target, and the specimen's share.
struct Price {
  bool affordable = false;
  double cost = std::numeric_limits<double>::infinity();
};
struct Error {
  double total = std::numeric_limits<double>::infinity(), specimen = 0;
};

// The search's candidates, a scene `s` with its bars at transit δ and its own specimen count, at
// s's Courant number. At asynchronous steps a bar's step and node updates are its own, and the
// model's bars' share does not see the specimen (it is on no pulse's path): the bars are planned
// and predicted once per (C, δ), the specimen once per (C, count), and a candidate adds them up —
// the numbers discretize() and predict() give for it, at a fraction of the cost (the search tries
// thousands: docs/methods.md §1.1, the cost of the choice). At global steps every bar steps at the
// smallest step, the specimen's included: each candidate is planned whole.
class Candidates {
 public:
  Candidates(const Scene& scene, SearchCache& cache)
      : cache_(cache),
        duration_s_(run_duration_s(scene)),
        sample_s_(1 / scene.simulation.sample_rate_Hz),
        separable_(scene.simulation.stepping == Stepping::kAsynchronous),
        specimen_(scene.specimen) {}

  Price price(Scene& s, const std::vector<bool>& free, double delta) {
    mesh_bars(s, free, delta);
    if (!separable_) {
      whole_ = plan_chain(s, duration_s_);
      return priced(whole_);
    }
    const Bars& b = bars(s, delta);
    if (!specimen_) return priced(b.plan);
    const ChainEstimates e = estimates_with_bar(b.plan, *specimen_, specimen(s).bar);
    return e.affordable ? Price{true, e.node_updates} : Price{};
  }

  // After price(s, free, delta) of the same s and δ.
  Error error(const Scene& s, double delta, PredictMode mode) {
    if (!separable_) {
      const GaugeErrorPrediction p = predict(s, whole_, kMeshErrorConstants, &cache_, mode);
      return {p.total, p.specimen};
    }
    Bars& b = bars(s, delta);
    const double spec = specimen_ ? specimen(s).share : 0.0;
    auto it = b.shares.find(mode.above);
    if (it == b.shares.end()) {
      PredictMode alone = mode;
      alone.bars_alone = true;
      const Predicted p = predict(s, b.plan, kMeshErrorConstants, &cache_, alone);
      it = b.shares.emplace(mode.above, Share{p.bars, p.bars_exact}).first;
    }
    // A bound shows a miss whatever the specimen (PredictMode::bars_alone).
    if (!it->second.exact) return {std::numeric_limits<double>::infinity(), spec};
    return {combined_error(it->second.bars, spec, b.others), spec};
  }

  // The specimen's share at s's count (after price() of s).
  double specimen_share(const Scene& s) {
    if (!specimen_) return 0.0;
    if (!separable_) return law_bar_share(whole_.bars[*specimen_], sample_s_, kMeshErrorConstants);
    return specimen(s).share;
  }

 private:
  struct Share {
    double bars = 0;
    bool exact = false;
  };
  struct Bars {
    ChainDiscretization plan;        // with whatever specimen count planned it first
    double others = 0;               // Σ e² of the other law bars
    std::map<double, Share> shares;  // the bars' share by the target it was bounded for
  };
  struct Specimen {
    BarDiscretization bar;
    double share = 0;
  };

  static double courant_of(const Scene& s) { return s.simulation.courant.value_or(0.0); }
  static Price priced(const ChainDiscretization& d) {
    return affordable(d) ? Price{true, d.node_updates_estimate} : Price{};
  }

  Bars& bars(const Scene& s, double delta) {
    const auto key = std::make_pair(courant_of(s), delta);
    auto it = bars_.find(key);
    if (it == bars_.end()) {
      Bars b{plan_chain(s, duration_s_), 0.0, {}};
      b.others = other_law_bars(s, b.plan, sample_s_, kMeshErrorConstants);
      if (specimen_) remember_specimen(s, b.plan);
      it = bars_.emplace(key, std::move(b)).first;
    }
    return it->second;
  }

  const Specimen& specimen(const Scene& s) {
    const auto key = std::make_pair(courant_of(s), s.bars[*specimen_].elements);
    auto it = specimens_.find(key);
    if (it == specimens_.end()) it = remember_specimen(s, plan_chain(s, duration_s_));
    return it->second;
  }

  std::map<std::pair<double, int>, Specimen>::iterator remember_specimen(
      const Scene& s, const ChainDiscretization& d) {
    const BarDiscretization& b = d.bars[*specimen_];
    return specimens_
        .try_emplace(std::make_pair(courant_of(s), b.elements),
                     Specimen{b, law_bar_share(b, sample_s_, kMeshErrorConstants)})
        .first;
  }

  SearchCache& cache_;
  const double duration_s_, sample_s_;
  const bool separable_;
  const std::optional<std::size_t> specimen_;
  std::map<std::pair<double, double>, Bars> bars_;
  std::map<std::pair<double, int>, Specimen> specimens_;
  ChainDiscretization whole_;  // global steps: the last candidate priced
};

// Specimen element counts tried (a geometric ladder, each count once), or the user's (0).
std::vector<int> specimen_ladder(const Scene& scene, const std::vector<bool>& free) {
  if (!scene.specimen || !free[*scene.specimen]) return {0};
  std::vector<int> counts;
  for (double n = 4; n <= 4000; n *= 1.15)
    if (counts.empty() || counts.back() != static_cast<int>(n))
      counts.push_back(static_cast<int>(n));
  return counts;
}

// The scan's first transit: the first of its points (from the coarsest down by kScanRatio) at or
// below the pulse's floor.
double scan_start(double coarsest, double floor, double finest) {
  double start = coarsest;
  while (start > floor && start / kScanRatio > finest) start /= kScanRatio;
  return start;
}

// Near C = 1 (kNearExactCourant): the bars of `s` at transits T/k of their common transit T,
// k = 1, 2, … (none coarser than `coarsest`) up to the first that meets the target, kept in
// `best` if cheaper than `best_cost`.
void near_exact(const Scene& s, const std::vector<bool>& free, double common, double coarsest,
                double target, PredictMode mode, Candidates& candidates, double& best_cost,
                Scene& best) {
  Scene near = s;
  near.simulation.courant = kNearExactCourant;
  for (long k = 1; k <= kMaxCommonDivisions; ++k) {
    if (common / k > coarsest) continue;  // coarser than a compliant link or the pulse allows
    const Price price = candidates.price(near, free, common / k);
    if (!price.affordable) break;
    if (price.cost >= best_cost) break;  // finer only costs more
    const Error e = candidates.error(near, common / k, mode);
    if (!(e.specimen <= target)) break;  // the specimen's share alone is too much
    if (e.total <= target) {
      best_cost = price.cost, best = near;
      break;
    }
  }
}

// The order a pruned search tries the specimen counts in: from the one whose share is nearest
// target/√2 (where neither the bars nor the specimen take the whole error) outwards. A candidate
// near the cheapest found first lets the cost bound cut the others short: the same choice (the
// cheapest over every count), found with a fraction of the error integrals.
std::vector<int> trial_order(const Scene& scene, std::vector<int> counts,
                             const std::vector<bool>& free, double start, double target,
                             Candidates& candidates) {
  if (!scene.specimen || counts.size() < 2) return counts;
  std::vector<std::pair<double, int>> keyed;
  Scene s = scene;
  for (int ns : counts) {
    s.bars[*scene.specimen].elements = ns;
    candidates.price(s, free, start);
    keyed.emplace_back(std::abs(std::log(candidates.specimen_share(s) * std::sqrt(2.0) / target)),
                       ns);
  }
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < counts.size(); ++i) counts[i] = keyed[i].second;
  return counts;
}

// The finest affordable element transit (refusal by discretize() is monotone in δ) between
// `finest` and `coarsest`, within kSearchRatio; none if not even `coarsest` is.
template <class Affordable>
std::optional<double> finest_affordable(Affordable&& affordable, double finest, double coarsest) {
  if (affordable(finest)) return finest;
  if (!affordable(coarsest)) return std::nullopt;
  double a = finest, b = coarsest;
  while (b / a > kSearchRatio) {
    const double mid = std::sqrt(a * b);
    (affordable(mid) ? b : a) = mid;
  }
  return b;
}

// choose_meshes() made afresh (its contract: model/mesh_choice.hpp).
GaugeErrorPrediction search_meshes(Scene& scene) {
  const double asked = scene.simulation.tolerance.value_or(0);
  std::vector<bool> free(scene.bars.size());
  for (std::size_t i = 0; i < scene.bars.size(); ++i) free[i] = scene.bars[i].elements == 0;
  const auto striker = striker_bar(scene);
  if (!striker) return predict_gauge_error(scene, discretize(scene));  // NaN: nothing to predict

  const std::vector<int> specimen_counts = specimen_ladder(scene, free);
  const std::optional<double> common = near_exact_transit_s(scene, free);
  // Element transits h/c tried for the bars: from one element per bar (at most half a compliant
  // link's rise time, kRiseTimeTransits) down to 1e-7 of the longest bar's, none coarser than the
  // pulse's floor (kElementsPerPulse): the scan's points stay those from the coarsest.
  const double coarsest = coarsest_transit_s(scene), finest = longest_transit_s(scene) * 1e-7;
  const double floor = pulse_floor_transit_s(scene);
  const double start = scan_start(coarsest, floor, finest);

  SearchCache cache;
  Candidates candidates(scene, cache);
  double closest = std::numeric_limits<double>::infinity();  // when none meets the tolerance
  Scene most_accurate = scene;
  // The cheapest mesh predicted at most `target` into `best`; false if there is none. `prune`:
  // leave out what cannot beat the best found so far (a specimen whose share alone misses the
  // target; meshes costing more than the best; meshes whose bound on the error misses) — the
  // same choice, and `closest` then not the lowest error (computed again without it if needed).
  const auto cheapest = [&](double target, Scene& best, bool prune) {
    double best_cost = std::numeric_limits<double>::infinity();
    PredictMode mode;
    if (prune) mode.above = target;
    // One candidate scene for every count: each sets its specimen's elements, and every pricing
    // meshes the other free bars afresh (mesh_bars), so nothing of the previous count remains.
    Scene s = scene;
    for (int ns : prune ? trial_order(scene, specimen_counts, free, start, target, candidates)
                        : specimen_counts) {
      if (ns > 0) s.bars[*scene.specimen].elements = ns;
      double cost = 0;  // the node updates of the last candidate priced
      const auto affordable = [&](double delta) {
        const Price p = candidates.price(s, free, delta);
        cost = p.cost;
        return p.affordable;
      };
      const auto error_at = [&](double delta) {
        return affordable(delta) ? candidates.error(s, delta, mode).total
                                 : std::numeric_limits<double>::infinity();
      };
      // Pruned: the specimen's share alone misses the target (the total is at least that share).
      if (prune && affordable(start) && !(candidates.specimen_share(s) <= target)) continue;
      if (common)
        near_exact(s, free, *common, std::min(coarsest, floor), target, mode, candidates, best_cost,
                   best);
      // The finest affordable element transit (refusal by discretize() is monotone in δ), found
      // only when the scan comes near it: the bisection ends within kSearchRatio above the
      // boundary, so a transit x whose x / kSearchRatio is affordable lies above it.
      std::optional<std::optional<double>> fine_found;
      bool none_affordable = false;
      const auto fine = [&] {
        if (!fine_found) fine_found = finest_affordable(affordable, finest, coarsest);
        none_affordable = !fine_found->has_value();
        return fine_found->value_or(finest);
      };
      // max(fine, x), and in `above` whether x is above fine.
      const auto clamp_fine = [&](double x, bool& above) {
        if (!fine_found && x / kSearchRatio >= finest && affordable(x / kSearchRatio)) {
          above = true;
          return x;
        }
        const double f = fine();
        above = x > f;
        return std::max(f, x);
      };
      bool above = false;
      // … then from the coarsest transit down, a step of kScanRatio at a time, to the first that
      // meets the target, and bisection back to its coarser neighbour: the error is not monotone
      // in δ (the fronts' dispersion falls with it, their aliasing in the record grows). Pruned,
      // the scan stops where a mesh costs the best found: every finer one costs more.
      double lo = clamp_fine(start, above), hi = lo;
      if (none_affordable) continue;
      const bool priced_out = prune && affordable(lo) && !(cost < best_cost);
      double e = priced_out ? std::numeric_limits<double>::infinity() : error_at(lo);
      Scene closest_here = prune ? Scene{} : s;  // pruned: `closest` is not asked for
      double closest_e = e;
      while (!priced_out && !(e <= target) && above) {
        // Pruned: a failing mesh costing the best already: every finer one (and the bisection
        // below it) costs more.
        if (prune && !(cost < best_cost)) break;
        hi = lo;
        lo = clamp_fine(lo / kScanRatio, above);
        e = error_at(lo);
        if (!prune && e < closest_e) closest_e = e, closest_here = s;
      }
      if (!prune && !(e <= target) && closest_e < closest)
        closest = closest_e, most_accurate = closest_here;
      if (e <= target) {
        while (hi / lo > kSearchRatio) {
          const double mid = std::sqrt(lo * hi);
          (error_at(mid) <= target ? lo : hi) = mid;
        }
        error_at(lo);
        if (cost < best_cost) best_cost = cost, best = s;
      }
    }
    return std::isfinite(best_cost);
  };
  // With the margin of the model's scatter if any mesh allows it; else (the bars the user meshed,
  // or the record's aliasing of sharp fronts, leave no room for it) halfway between the best
  // predicted error and the tolerance; else the most accurate mesh (refused by resolve_scene()).
  Scene best = scene;
  bool found = cheapest(kTargetFraction * asked, best, true);
  if (!found) {
    closest = std::numeric_limits<double>::infinity();
    cheapest(kTargetFraction * asked, best, false);  // the lowest error, unpruned
    found = closest <= asked && cheapest(0.5 * (closest + asked), best, false);
  }
  if (found)
    scene = best;
  else if (std::isfinite(closest))
    scene = most_accurate;
  return predict(scene, discretize(scene), kMeshErrorConstants, &cache);
}

// The choices made before, by the whole scene they were made for (every field, compared by the
// structs' defaulted ==, so a field added to the scene is in the key without a list to keep): a
// loop over one scene (a notebook's cell run again, a benchmark) finds its choice in a few µs,
// where the search takes 0.3–0.8 ms on the classic experiment, and an edit anywhere (a velocity,
// a law's parameter, a gauge) is searched for afresh. The search is a pure function of the scene
// (its integrals remembered by their numbers, front_error.hpp), so a choice found again is the one
// the search would make. The last kRemembered, first in first out, one memo per process.
class MeshChoiceMemo {
 public:
  std::optional<std::pair<Scene, GaugeErrorPrediction>> find(const Scene& asked) {
    const std::lock_guard<std::mutex> hold(lock_);
    for (const Entry& e : entries_)
      if (e.asked == asked) return std::pair{e.chosen, e.prediction};
    return std::nullopt;
  }
  void keep(const Scene& asked, const Scene& chosen, const GaugeErrorPrediction& prediction) {
    const std::lock_guard<std::mutex> hold(lock_);
    if (entries_.size() == kRemembered) entries_.pop_front();
    entries_.push_back({asked, chosen, prediction});
  }
  void clear() {
    const std::lock_guard<std::mutex> hold(lock_);
    entries_.clear();
  }

 private:
  // Enough for the scenes a session alternates between; the draws of a Monte Carlo or a fit
  // (every scene new) pay a copy and at most this many comparisons per search.
  static constexpr std::size_t kRemembered = 16;
  struct Entry {
    Scene asked, chosen;
    GaugeErrorPrediction prediction;
  };
  std::mutex lock_;
  std::deque<Entry> entries_;
};

MeshChoiceMemo& choices() {
  static MeshChoiceMemo memo;
  return memo;
}

}  // namespace

GaugeErrorPrediction choose_meshes(Scene& scene) {
  if (auto found = choices().find(scene)) {
    scene = std::move(found->first);
    return found->second;
  }
  const Scene asked = scene;
  const GaugeErrorPrediction prediction = search_meshes(scene);
  choices().keep(asked, scene, prediction);
  return prediction;
}

void forget_mesh_choices() { choices().clear(); }

}  // namespace shpb