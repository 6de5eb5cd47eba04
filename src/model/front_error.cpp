#include "model/front_error.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <mutex>
#include <unordered_map>

namespace shpb {

namespace {

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

// The integral checks its sum against the give-up bound every this many points.
constexpr int kGiveUpStride = 32;

// The cut-off 2 asin(C)/Δt of a bar's mesh: no higher frequency is carried.
double cutoff_of(const FrontPath::Bar& b) {
  return 2 * std::asin(std::min(b.courant, 1.0)) / b.time_step_s;
}

double aliased_error_s(const FrontPath& p, const FrequencyWeights& f) {
  double cutoff = std::numeric_limits<double>::infinity();
  for (const FrontPath::Bar& b : p.bars)
    if (b.x > 0) cutoff = std::min(cutoff, cutoff_of(b));
  // The running sum up to the first point at or above the cut-off.
  const auto n =
      std::lower_bound(f.alias_w.begin(), f.alias_w.end() - 1, cutoff) - f.alias_w.begin();
  return f.alias_sum[n] * f.alias_dw / M_PI;
}

// What front_error_s returns for any give-up bound: the sums it compares with the bound, in
// order, and (complete) the integral; incomplete, it stopped at its last sum.
struct Trace {
  std::array<double, kFrequencyPoints / kGiveUpStride> sums{};
  int count = 0;  // of sums
  double value = 0;
  bool complete = false;
};

// The integral itself (docs/methods.md §1.1): each bar's sin(ωΔt/2) by angle addition from one
// frequency to the next; the gauge's filter F from sin(κh/2) = s itself. Out of line: inlined
// into the memo's lookup it took 15 % more instructions (measured on the classic choice).
[[gnu::noinline]] void integrate(const FrontPath& p, const FrequencyWeights& f, double give_up,
                                 Trace& t) {
  struct PathBar {
    double x, courant, two_over_h, slowness, half_step;
    std::complex<double> rotation, phasor;  // e^{i dω Δt/2}, e^{i ω Δt/2}
    bool gauge;
  };
  std::vector<PathBar> path;
  double h = 0;
  const double gauge_w = p.gauge_w;  // in a register, not read through `p` at every frequency
  path.reserve(p.bars.size());
  for (const FrontPath::Bar& b : p.bars) {
    const double half_step = 0.5 * f.dw * b.time_step_s;
    path.push_back({b.x,
                    b.courant,
                    2 / b.element_length_m,
                    1 / b.wave_speed_m_s,
                    half_step,
                    std::polar(1.0, half_step),
                    {1.0, 0.0},
                    b.gauge});
    if (b.gauge) h = b.element_length_m;
  }
  // The sums kept in locals while integrating, copied into `t` at the end.
  std::array<double, kFrequencyPoints / kGiveUpStride> sums;
  int count = 0;
  const auto keep = [&](double value, bool complete) {
    std::copy_n(sums.begin(), count, t.sums.begin());
    t.count = count, t.value = value, t.complete = complete;
  };
  double sum = 0;
  int j = 1;
  for (; j <= kFrequencyPoints; ++j) {
    const double w = j * f.dw;
    double phase = 0, sg = 0, kg = 0;
    bool carried = true;
    for (PathBar& b : path) {
      b.phasor *= b.rotation;
      if (!(j * b.half_step < 0.5 * M_PI)) {
        carried = false;  // above the mesh's cut-off: the frequency never reaches the gauge
        break;
      }
      const double s = b.phasor.imag() / b.courant;
      if (s >= 1) {
        carried = false;
        break;
      }
      const double k = b.two_over_h * std::asin(s);
      phase += b.x * (k - w * b.slowness);
      if (b.gauge) sg = s, kg = k;
    }
    // Above the lowest cut-off nothing is carried at any higher frequency either: the tail sum.
    if (!carried) break;
    // The gauge reads element strains (each the mean over its element: sinc(κh/2)) interpolated
    // linearly between the centres around it, at fraction w of the pitch: the centres' values
    // lead and lag the gauge's own by w·h and (1 − w)·h, so
    //   F = sinc(κh/2) ((1 − w) e^{iκwh} + w e^{−iκ(1−w)h})   (at C = 1 exactly what is left),
    // with sin(κh/2) = s and e^{−iκh} = (cos(κh/2) − i s)²; F H = sinc · e^{i(φ + κwh)} ·
    // ((1 − w) + w e^{−iκh}).
    const double kh = kg * h;
    const double sinc = kh > 1e-8 ? 2 * sg / kh : 1.0;
    const std::complex<double> back(std::sqrt(std::max(0.0, 1 - sg * sg)), -sg);
    const double miss = std::norm(sinc * std::polar(1.0, phase + kh * gauge_w) *
                                      ((1 - gauge_w) + gauge_w * (back * back)) -
                                  1.0);
    sum += f.weight[j] * miss / f.w2[j];
    if (j % kGiveUpStride == 0) {
      const double so_far = sums[count++] = sum * f.dw / M_PI;
      if (so_far > give_up) return keep(0.0, false);
    }
  }
  if (j <= kFrequencyPoints) sum += f.tail[j];
  keep(sum * f.dw / M_PI + (p.aliasing > 0 ? p.aliasing * aliased_error_s(p, f) : 0.0), true);
}

// What the integral returns for `give_up`, if the trace tells.
bool answer(const Trace& t, double give_up, double& value, bool& gave_up) {
  for (int i = 0; i < t.count; ++i)
    if (t.sums[i] > give_up) {
      value = t.sums[i], gave_up = true;
      return true;
    }
  value = t.value, gave_up = false;
  return t.complete;
}

// Every number the integral reads, bit for bit (−0 is not +0 here: equal keys, equal inputs).
using Key = std::vector<std::uint64_t>;
static_assert(sizeof(FrontPath) == 2 * sizeof(double) + sizeof(std::vector<FrontPath::Bar>) &&
                  sizeof(FrontPath::Bar) == 6 * sizeof(double),
              "a number added to FrontPath is read by the integral: add it to key_of()");
void key_of(const FrontPath& p, const FrequencyWeights& f, Key& key) {
  key.clear();
  const auto add = [&](double v) { key.push_back(std::bit_cast<std::uint64_t>(v)); };
  add(f.sample_s), add(f.rise_s), add(p.aliasing), add(p.gauge_w);
  for (const FrontPath::Bar& b : p.bars) {
    add(b.x), add(b.courant), add(b.element_length_m), add(b.wave_speed_m_s), add(b.time_step_s);
    key.push_back(b.gauge ? 1 : 0);
  }
}
struct KeyHash {
  std::size_t operator()(const Key& key) const {
    std::uint64_t h = 0x9e3779b97f4a7c15u;
    for (const std::uint64_t v : key) h = (h ^ v) * 0xff51afd7ed558ccdu, h ^= h >> 32;
    return static_cast<std::size_t>(h);
  }
};

// Bounded: forgotten whole past this many paths (a classic choice integrates about a hundred;
// each a few hundred bytes).
constexpr std::size_t kRememberedPaths = 4096;
// The paths asked for once, a word each in a direct-mapped table of this many (a power of 2).
constexpr std::size_t kSeenPaths = 8192;
// The weights of this many (Δs, τ) pairs are kept.
constexpr std::size_t kRememberedWeights = 8;

// One per process, under a lock held only to look up and to store (the integral is computed
// outside it): Python threads run simulations in parallel, and a pool's threads or a study's
// workers should find what another thread's run remembered.
// Measured on the classic choice, two threads at once: 0.38–0.39 ms a choice against 0.35–0.37 ms
// with a memo per thread (docs/methods.md §1.1, the cost of the choice).
struct Memo {
  std::mutex lock;
  std::unordered_map<Key, Trace, KeyHash> traces;
  std::vector<std::size_t> seen;  // the hashes of paths asked for (| 1: 0 is none)
  std::vector<std::shared_ptr<const FrequencyWeights>> weights;  // the most recent last
};
Memo& memo() {
  static Memo kept;  // built on first use, whatever the order of static initialisation
  return kept;
}

}  // namespace

FrequencyWeights::FrequencyWeights(double sample, double rise) : sample_s(sample), rise_s(rise) {
  dw = kFrequencyEnd / sample_s / kFrequencyPoints;
  weight.assign(kFrequencyPoints + 1, 0.0);
  w2.assign(kFrequencyPoints + 1, 0.0);
  tail.assign(kFrequencyPoints + 2, 0.0);
  for (int j = 1; j <= kFrequencyPoints; ++j) {
    const double w = j * dw;
    w2[j] = w * w;
    weight[j] = (j == kFrequencyPoints ? 0.5 : 1) *
                (std::exp(-w * w * sample_s * sample_s) / (1 + w * w * rise_s * rise_s));
  }
  for (int j = kFrequencyPoints; j >= 1; --j) tail[j] = tail[j + 1] + weight[j] / w2[j];
  const double images = 2 * M_PI / sample_s;
  const double top = (kAliasImages + 0.5) * images;
  alias_dw = kAliasStep / sample_s;
  double sum = 0;
  for (double w = 0.5 * M_PI / sample_s; w < top; w += alias_dw) {
    alias_w.push_back(w);
    alias_sum.push_back(sum);
    const double m = std::max(1.0, std::round(w / images));  // the nearest image dominates
    double wt = 0;
    for (double k = std::max(1.0, m - 1); k <= m + 1; ++k)
      wt += std::exp(-std::pow((w - k * images) * sample_s, 2));
    sum += wt / (w * w * (1 + w * w * rise_s * rise_s));
  }
  alias_w.push_back(top);
  alias_sum.push_back(sum);
}

std::shared_ptr<const FrequencyWeights> frequency_weights(double sample_s, double rise_s) {
  Memo& m = memo();
  const std::lock_guard hold(m.lock);
  auto& kept = m.weights;
  const auto same = [&](const auto& f) {
    return std::bit_cast<std::uint64_t>(f->sample_s) == std::bit_cast<std::uint64_t>(sample_s) &&
           std::bit_cast<std::uint64_t>(f->rise_s) == std::bit_cast<std::uint64_t>(rise_s);
  };
  if (const auto it = std::find_if(kept.begin(), kept.end(), same); it != kept.end()) {
    std::rotate(it, it + 1, kept.end());
    return kept.back();
  }
  if (kept.size() >= kRememberedWeights) kept.erase(kept.begin());
  kept.push_back(std::make_shared<const FrequencyWeights>(sample_s, rise_s));
  return kept.back();
}

double front_error_s(const FrontPath& p, const FrequencyWeights& f, double give_up, bool* gave_up) {
  thread_local Key key;  // its storage reused
  key_of(p, f, key);
  Memo& m = memo();
  double value = 0;
  bool stopped = false;
  {
    const std::lock_guard hold(m.lock);
    if (const auto it = m.traces.find(key);
        it != m.traces.end() && answer(it->second, give_up, value, stopped)) {
      if (gave_up) *gave_up = stopped;
      return value;
    }
  }
  Trace t;
  integrate(p, f, give_up, t);
  answer(t, give_up, value, stopped);
  if (gave_up) *gave_up = stopped;
  const std::lock_guard hold(m.lock);
  // Kept from the second time a path is asked for: every path of a Monte Carlo draw (a bar
  // length drawn anew each run) is asked for once, and keeping each one's integral slowed such
  // runs of the classic choice by 13–18 % (the memo's writes pushed the search's own data out of
  // the cache; a word per path: under 1 %). Another path of the same hash seen instead only keeps
  // an integral early.
  if (m.seen.empty()) m.seen.assign(kSeenPaths, 0);
  const std::size_t hash = KeyHash{}(key);
  if (std::size_t& seen = m.seen[hash & (kSeenPaths - 1)]; seen != (hash | 1)) {
    seen = hash | 1;
    return value;
  }
  if (m.traces.size() >= kRememberedPaths) m.traces.clear();
  // A trace that stopped short replaced by a longer one (the same sums, then more), never the
  // other way round (another thread may have stored it meanwhile).
  const auto [it, added] = m.traces.try_emplace(key, t);
  if (!added && !it->second.complete && (t.complete || t.count > it->second.count)) it->second = t;
  return value;
}

double front_error_floor_s(const FrontPath& p, const FrequencyWeights& f) {
  double cutoff = std::numeric_limits<double>::infinity();
  for (const FrontPath::Bar& b : p.bars) cutoff = std::min(cutoff, cutoff_of(b));
  const double first = std::ceil(cutoff / f.dw) + 1;  // the point at the cut-off may be carried
  const double tail =
      first > kFrequencyPoints ? 0.0 : f.tail[static_cast<std::size_t>(std::max(1.0, first))];
  return tail * f.dw / M_PI + (p.aliasing > 0 ? p.aliasing * aliased_error_s(p, f) : 0.0);
}

void forget_front_errors() {
  Memo& m = memo();
  const std::lock_guard hold(m.lock);
  m.traces.clear();
  m.seen.clear();
  m.weights.clear();
}

}  // namespace shpb
