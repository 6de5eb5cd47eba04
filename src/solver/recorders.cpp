#include "solver/recorders.hpp"

#include <algorithm>
#include <cmath>

#include "core/finite_values.hpp"
#include "core/interpolation.hpp"
#include "core/record_filter.hpp"
#include "output_schema.hpp"
#include "solver/bar_integrator.hpp"
#include "solver/end_segment.hpp"

namespace shpb {

namespace {
// The energy history has at most this many points (it is checked for instability there, and
// each point costs one pass over the active nodes of every bar).
constexpr long kEnergyPoints = 200;
// A field row needs at least this many points per bar so that short bars (the specimen) show.
constexpr int kMinFieldPointsPerBar = 5;
// Gauge grid points per sample of a filtered record (gauges_filtered): the record's Gaussian
// spans ±4 samples, so 8 points per sample resolve it (as the study's references, which are
// recorded at 8 × the rate and smoothed the same way: study/reference.hpp).
constexpr int kGaugeOversampling = 8;
// specimen.csv: strain, strain_rate_1_s, stress_Pa, front_stress_Pa, back_stress_Pa, true_strain,
// true_stress_Pa.
constexpr int kSpecimenColumns = 7;

long grid_count(double span, double spacing) {
  return span < 0 ? 0 : static_cast<long>(std::floor(span / spacing + 1e-9)) + 1;
}

// Keeps the rows before the first non-finite value of any column (an unstable run's tail).
void keep_finite_prefix(TimeSeries& ts) {
  std::size_t n = ts.time_s.size();
  for (const auto& col : ts.values)
    n = std::min(n, first_non_finite({col.data(), std::min(n, col.size())}));
  ts.time_s.resize(n);
  for (auto& col : ts.values) col.resize(std::min(n, col.size()));
}
}  // namespace

GridSampler::GridSampler(double tau0, double spacing, long count, int width)
    : tau0_(tau0),
      spacing_(spacing),
      count_(std::max(0L, count)),
      width_(width),
      prev_(width, 0.0),
      data_(static_cast<std::size_t>(count_) * width, 0.0) {}

void GridSampler::push(double tau, const double* values) {
  while (filled_ < count_ && next_tau() <= tau) {
    double* out = &data_[filled_ * width_];
    const double t = next_tau();
    if (has_prev_ && tau > prev_tau_) {
      const double a = (t - prev_tau_) / (tau - prev_tau_);
      for (int c = 0; c < width_; ++c) out[c] = lerp(prev_[c], values[c], a);
    } else {
      for (int c = 0; c < width_; ++c) out[c] = values[c];
    }
    ++filled_;
  }
  std::copy(values, values + width_, prev_.begin());
  prev_tau_ = tau;
  has_prev_ = true;
}

std::vector<double> GridSampler::column(int c, long n) const {
  std::vector<double> v(n);
  for (long k = 0; k < n; ++k) v[k] = at(k, c);
  return v;
}

ChainRecorders::ChainRecorders(const Scene& scene, const Chain& chain, const ChainDiscretization& d,
                               const SimulationOptions& options) {
  sample_spacing_s_ = 1.0 / d.sample_rate_Hz;
  samples_ = grid_count(d.duration_s, sample_spacing_s_);
  energy_spacing_ = std::max(sample_spacing_s_, chain.end_tau_s / (kEnergyPoints - 1));
  energy_samples_ = grid_count(chain.end_tau_s, energy_spacing_);
  if (gauges_filtered(scene.simulation)) gauge_oversampling_ = kGaugeOversampling;
  record_field_ = options.record_field && options.field_times > 1 && options.field_points > 0;

  double total_length = 0;
  for (const BarModel& b : chain.bars) total_length += b.element_length_m * b.elements();
  double x_left = 0;
  bars_.resize(chain.bars.size());
  for (std::size_t i = 0; i < chain.bars.size(); ++i) {
    const BarModel& bar = chain.bars[i];
    BarRecorder& r = bars_[i];
    const double h = bar.element_length_m;
    const int ne = bar.elements();
    for (const GaugeSpec& g : scene.bars[i].gauges) {
      // Element strains are constant per element; a point gauge interpolates between centres.
      double s = g.position_m / h - 0.5;
      s = std::clamp(s, 0.0, static_cast<double>(ne - 1));
      int e = std::min(static_cast<int>(std::floor(s)), std::max(ne - 2, 0));
      r.gauges.push_back({gauge_names_.size(), e, ne > 1 ? s - e : 0.0});
      gauge_names_.push_back(g.name);
    }
    r.gauge_sampler =
        GridSampler(0.0, sample_spacing_s_ / gauge_oversampling_,
                    (samples_ - 1) * gauge_oversampling_ + 1, static_cast<int>(r.gauges.size()));
    r.specimen = scene.specimen && *scene.specimen == i;
    if (r.specimen)
      r.specimen_sampler = GridSampler(0.0, sample_spacing_s_, samples_, kSpecimenColumns);
    r.energy_sampler = GridSampler(0.0, energy_spacing_, energy_samples_, 3);
    if (record_field_) {
      const double length = h * ne;
      int points =
          std::max(kMinFieldPointsPerBar,
                   static_cast<int>(std::lround(options.field_points * length / total_length)));
      points = std::min(points, ne);
      r.field_offset = field_x_.size();
      for (int p = 0; p < points; ++p) {
        const int e = std::min(ne - 1, static_cast<int>((p + 0.5) * ne / points));
        r.field_elements.push_back(e);
        field_x_.push_back(x_left + (e + 0.5) * h);
      }
    }
    x_left += h * ne + (i < chain.interfaces.size() ? chain.interfaces[i].gap0_m : 0.0);
  }
  for (const InterfaceModel& m : chain.interfaces) {
    interface_names_.push_back(m.name);
    interfaces_.push_back({GridSampler(0.0, sample_spacing_s_, samples_, 2),
                           GridSampler(0.0, energy_spacing_, energy_samples_, 4)});
  }
  if (record_field_) {
    for (int j = 0; j < options.field_times; ++j)
      field_tau_.push_back(d.duration_s * j / (options.field_times - 1));
    field_stress_.assign(field_tau_.size() * field_x_.size(), 0.0);
  }
}

namespace {
// A bar end tied to a rigid frame at asynchronous steps (docs/methods.md §3.4) moved with the frame
// on the union of instants since the bar's last one; its half-step velocities v_{n∓1/2} are the
// frame's one bar step apart, so ½ m v_{n−1/2} v_{n+1/2} misses the energy the frame carried into
// the neighbour meanwhile (PMMA mini-Kolsky at C 0.9995: 0.8 % of the total at the first contact,
// back at the next instant). Its kinetic energy at τ is the frame's discrete one, ½ m v_f− v_f+.
// Zero at global steps (the two are the same velocities). A stiff finite link's end follows its
// half-frame at the link's rate (contact_localized_finite.cpp); end segments keep their own.
double tied_ends_kinetic_correction(const Chain& chain, std::size_t i, double tau) {
  const BarModel& bar = chain.bars[i];
  const BarState& st = chain.states[i];
  double correction = 0;
  for (int side = 0; side < 2; ++side) {  // side 0: node 0 (interface i − 1's right end)
    if (side == 0 && i == 0) continue;
    const std::size_t k = side == 0 ? i - 1 : i;
    if (k >= chain.interfaces.size() || chain.segment_at(k)) continue;
    const InterfaceState& is = chain.interface_states[k];
    const int link = side == 0 ? 1 : 0;  // this end's link at interface k
    if (std::isnan(tied_end_position(chain.interfaces[k], is, link, tau))) continue;
    // Finite links: the end follows its half-frame behind the link, at the link's rate.
    const double rate = chain.interfaces[k].finite_links ? is.link_v[link] : 0.0;
    const int node = side == 0 ? 0 : bar.nodes - 1;
    correction += 0.5 * bar.mass_kg[node] * (is.frame_v_before - rate) * (is.frame_v - rate) -
                  node_kinetic_energy(bar, st, node);
  }
  return correction;
}
}  // namespace

void ChainRecorders::on_bar_instant(const Chain& chain, std::size_t i, double tau_n,
                                    double tau_next) {
  const BarModel& bar = chain.bars[i];
  const BarState& s = chain.states[i];
  BarRecorder& r = bars_[i];
  const double inv_h = 1.0 / bar.element_length_m;
  if (!r.gauges.empty() && r.gauge_sampler.wants(tau_next)) {
    double values[64];
    std::vector<double> many;
    double* out = values;
    if (r.gauges.size() > 64) {
      many.resize(r.gauges.size());
      out = many.data();
    }
    const bool segmented = bar.segment_elements[0] > 0 || bar.segment_elements[1] > 0;
    const auto strain = [&](int e) {
      return segmented ? segmented_element_strain(chain, i, e, tau_n)
                       : (s.w[e + 1] - s.w[e]) * inv_h;
    };
    for (std::size_t g = 0; g < r.gauges.size(); ++g) {
      const GaugeProbe& p = r.gauges[g];
      const double e0 = strain(p.element);
      const double e1 = p.weight > 0 ? strain(p.element + 1) : e0;
      out[g] = (1 - p.weight) * e0 + p.weight * e1;
    }
    r.gauge_sampler.push(tau_n, out);
  }
  if (r.specimen && r.specimen_sampler.wants(tau_next)) {
    const int last = bar.nodes - 1;
    const double length = bar.element_length_m * bar.elements();
    double mean = 0, mean_true = 0;
    for (int e = 0; e < bar.elements(); ++e) {
      mean += element_engineering_stress(bar, s, e);
      mean_true += element_stress(bar, s, e);
    }
    mean /= bar.elements();
    mean_true /= bar.elements();
    // Compression positive (docs/outputs.md): engineering strain and stress (force over the
    // initial area), then logarithmic strain and the mean true stress (force over current area).
    const double strain = -(s.w[last] - s.w[0]) / length;
    const double values[kSpecimenColumns] = {
        strain,
        -(node_velocity_now(bar, s, last) - node_velocity_now(bar, s, 0)) / length,
        -mean,
        -element_engineering_stress(bar, s, 0),
        -element_engineering_stress(bar, s, bar.elements() - 1),
        -std::log1p(-strain),
        -mean_true};
    r.specimen_sampler.push(tau_n, values);
  }
  if (r.energy_sampler.wants(tau_next)) {
    BarEnergy e = bar_energy(bar, s);
    e.kinetic_J += tied_ends_kinetic_correction(chain, i, tau_n);
    const double values[3] = {e.kinetic_J, e.strain_J, e.dissipated_J + s.dissipated_J};
    r.energy_sampler.push(tau_n, values);
  }
  if (record_field_) {
    while (r.field_next < static_cast<long>(field_tau_.size()) &&
           field_tau_[r.field_next] <= tau_n) {
      double* row = &field_stress_[r.field_next * field_x_.size() + r.field_offset];
      for (std::size_t p = 0; p < r.field_elements.size(); ++p)
        row[p] = element_stress(bar, s, r.field_elements[p]);
      ++r.field_next;
    }
  }
}

void ChainRecorders::on_interface_solve(const Chain& chain, std::size_t k, double tau,
                                        double tau_next) {
  const InterfaceState& s = chain.interface_states[k];
  InterfaceRecorder& r = interfaces_[k];
  if (r.sampler.wants(tau_next)) {
    const double values[2] = {s.force_N, s.gap_m};
    r.sampler.push(tau, values);
  }
  if (r.energy_sampler.wants(tau_next)) {
    const double energy[4] = {s.energy_J, chain.contact_dissipated_J[k], s.segment_kinetic_J,
                              s.segment_strain_J};
    r.energy_sampler.push(tau, energy);
  }
}

long ChainRecorders::energy_complete() const {
  long n = energy_samples_;
  for (const BarRecorder& r : bars_) n = std::min(n, r.energy_sampler.filled());
  for (const InterfaceRecorder& r : interfaces_) n = std::min(n, r.energy_sampler.filled());
  return n;
}

double ChainRecorders::energy_total(long k) const {
  double total = 0;
  for (const BarRecorder& r : bars_)
    total += r.energy_sampler.at(k, 0) + r.energy_sampler.at(k, 1) + r.energy_sampler.at(k, 2);
  for (const InterfaceRecorder& r : interfaces_)
    total += r.energy_sampler.at(k, 0) + r.energy_sampler.at(k, 1) + r.energy_sampler.at(k, 2) +
             r.energy_sampler.at(k, 3);
  return total;
}

double ChainRecorders::energy_strain(long k) const {
  double strain = 0;
  for (const BarRecorder& r : bars_) strain += r.energy_sampler.at(k, 1);
  for (const InterfaceRecorder& r : interfaces_) strain += r.energy_sampler.at(k, 3);
  return strain;
}

void ChainRecorders::finish(const Chain&, double until_s, SimulationResult& result) {
  auto time_count = [&](long filled) {
    long n = std::min(filled, grid_count(until_s, sample_spacing_s_));
    return std::max(0L, n);
  };
  // The record's first n sample times (gauges, interfaces and specimen share the grid).
  auto sample_times = [&](long n) {
    std::vector<double> t(n);
    for (long k = 0; k < n; ++k) t[k] = k * sample_spacing_s_;
    return t;
  };
  // Gauges.
  {
    TimeSeries& ts = result.gauges;
    ts.columns = gauge_names_;
    const int os = gauge_oversampling_;
    long fine = (time_count(samples_) - 1) * os + 1;
    for (const BarRecorder& r : bars_)
      if (!r.gauges.empty()) fine = std::min(fine, r.gauge_sampler.filled());
    const long n = fine > 0 ? (fine - 1) / os + 1 : 0;
    ts.values.resize(gauge_names_.size());  // each column is one gauge's, filled below
    ts.time_s = sample_times(n);
    for (const BarRecorder& r : bars_)
      for (std::size_t g = 0; g < r.gauges.size(); ++g) {
        // Every fine point recorded (the Gaussian reaches past the last kept sample): at least
        // (n − 1)·os + 1 of them, so at least n smoothed samples.
        const GridSampler& sampler = r.gauge_sampler;
        const std::vector<double> copied =
            sampler.width() > 1 ? sampler.column(static_cast<int>(g), sampler.filled())
                                : std::vector<double>{};
        const std::span<const double> x = sampler.width() > 1 ? copied : sampler.rows();
        std::vector<double>& out = ts.values[r.gauges[g].column];
        if (os == 1) {
          out.assign(x.begin(), x.begin() + n);
          continue;
        }
        out = record_smoothed(x, os, os);
        out.resize(n);
      }
  }
  keep_finite_prefix(result.gauges);
  // Interfaces.
  {
    TimeSeries& ts = result.interfaces;
    long n = time_count(samples_);
    for (const InterfaceRecorder& r : interfaces_) n = std::min(n, r.sampler.filled());
    ts.time_s = sample_times(n);
    for (std::size_t i = 0; i < interfaces_.size(); ++i) {
      ts.columns.push_back(interface_names_[i] + "_force_N");
      ts.columns.push_back(interface_names_[i] + "_gap_m");
      for (int c = 0; c < 2; ++c) ts.values.push_back(interfaces_[i].sampler.column(c, n));
    }
  }
  keep_finite_prefix(result.interfaces);
  // Specimen.
  for (const BarRecorder& r : bars_) {
    if (!r.specimen) continue;
    TimeSeries& ts = result.specimen;
    namespace k = schema::specimen;  // the column names (src/core/output_schema.json)
    ts.columns = {k::strain,         k::strain_rate_1_s, k::stress_Pa,     k::front_stress_Pa,
                  k::back_stress_Pa, k::true_strain,     k::true_stress_Pa};
    const long n = time_count(r.specimen_sampler.filled());
    ts.time_s = sample_times(n);
    for (int c = 0; c < kSpecimenColumns; ++c) ts.values.push_back(r.specimen_sampler.column(c, n));
  }
  keep_finite_prefix(result.specimen);
  // Energy.
  {
    TimeSeries& ts = result.energy;
    namespace k = schema::energy;
    ts.columns = {k::kinetic_J, k::strain_J, k::contact_J, k::dissipated_J, k::total_J};
    ts.values.assign(5, {});
    const long n = energy_complete();
    for (long k = 0; k < n; ++k) {
      const double t = energy_grid_tau(k);
      if (t > until_s + 1e-12) break;
      double kin = 0, strain = 0, contact = 0, diss = 0;
      for (const BarRecorder& r : bars_) {
        kin += r.energy_sampler.at(k, 0);
        strain += r.energy_sampler.at(k, 1);
        diss += r.energy_sampler.at(k, 2);
      }
      for (const InterfaceRecorder& r : interfaces_) {
        contact += r.energy_sampler.at(k, 0);
        diss += r.energy_sampler.at(k, 1);
        kin += r.energy_sampler.at(k, 2);  // an end segment's bar energy (end_segment.hpp)
        strain += r.energy_sampler.at(k, 3);
      }
      ts.time_s.push_back(t);
      ts.values[0].push_back(kin);
      ts.values[1].push_back(strain);
      ts.values[2].push_back(contact);
      ts.values[3].push_back(diss);
      ts.values[4].push_back(kin + strain + contact + diss);
    }
  }
  keep_finite_prefix(result.energy);
  // Field: the rows before the first with a non-finite value.
  if (record_field_) {
    long rows = static_cast<long>(field_tau_.size());
    for (const BarRecorder& r : bars_) rows = std::min(rows, r.field_next);
    FieldGrid& f = result.field;
    for (long j = 0; j < rows; ++j) {
      const double t = field_tau_[j];
      if (t > until_s + 1e-12) break;
      f.time_s.push_back(t);
    }
    const std::size_t nx = field_x_.size();
    if (nx > 0)
      f.time_s.resize(first_non_finite({field_stress_.data(), f.time_s.size() * nx}) / nx);
    f.stress_Pa = std::move(field_stress_);  // the grid's layout: no copy
    f.stress_Pa.resize(f.time_s.size() * nx);
    f.x_m = std::move(field_x_);
  }
}

}  // namespace shpb
