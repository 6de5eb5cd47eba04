// The uncertain inputs of a measured test (analysis/uncertainty_inputs.hpp).
#include "analysis/uncertainty_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "analysis/dispersion_cutoff.hpp"
#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"
#include "core/units.hpp"
#include "model/uncertainty_reader.hpp"

namespace shpb {
namespace {

double absolute(const StandardUncertainty& u, double nominal) {
  return u.relative ? u.value * std::abs(nominal) : u.value;
}

std::string unit_of(Dimension d) { return std::string(si_unit(d)); }

// The inputs, appended in the order they are applied to a draw (a zero uncertainty adds none).
// A positive input's standard uncertainty must keep its draws > 0 (sign_keeping_problem):
// refused (exit 2, naming the scene's JSON path) before any draw.
struct InputList {
  std::string file;  // the scene
  std::vector<Input> in;
  void add(std::string name, double value, double sigma, Dimension d, const std::string& path,
           bool positive, std::function<void(double, DrawState&)> apply) {
    if (!(sigma > 0)) return;
    if (positive)
      if (const std::string what = sign_keeping_problem(value, sigma, d); !what.empty())
        throw input_error(file, path, JsonValue::format(sigma, d), what);
    in.push_back({{std::move(name), path, value, sigma, unit_of(d)}, positive, std::move(apply)});
  }
};

// Bridge factors: ε = k V/(GF gain V_ex), so a drawn factor x scales the strain by x0/x. A factor
// named in `shared` is one draw for every channel (channel c's value x0_c + σ_c z with the same
// standard normal z): the strains then scale together, which independent draws average away —
// the 3-wave stress's uncertainty from a shared 1 % gauge factor is 1 %, from independent ones
// about 0.7 % (docs/methods.md §10).
void add_bridge_inputs(InputList& in, const UncertaintySpec& u, const MeasurementSpec& m) {
  struct Factor {
    const char* key;
    const char* words;
    const std::optional<StandardUncertainty>* spec;
    double BridgeSpec::*value;
    Dimension dim;
    bool shared;
  };
  auto is_shared = [&](const char* key) {
    return std::find(u.shared.begin(), u.shared.end(), key) != u.shared.end();
  };
  const Factor factors[] = {
      {"gauge_factor", "gauge factor", &u.gauge_factor, &BridgeSpec::gauge_factor,
       Dimension::kDimensionless, is_shared("gauge_factor")},
      {"excitation", "bridge excitation", &u.excitation, &BridgeSpec::excitation_V,
       Dimension::kVoltage, is_shared("excitation")},
      {"gain", "amplifier gain", &u.gain, &BridgeSpec::gain, Dimension::kDimensionless,
       is_shared("gain")}};
  // Per channel first, channel by channel (the order of the draws), then the shared factors.
  for (std::size_t c = 0; c < m.channels.size(); ++c) {
    const ChannelSpec& ch = m.channels[c];
    if (!ch.bridge) continue;
    for (const Factor& f : factors)
      if (*f.spec && !f.shared) {
        const double x0 = (*ch.bridge).*f.value;
        in.add(
            std::string(f.words) + " of channel " + std::to_string(c) + " (gauge " + ch.gauge + ")",
            x0, absolute(**f.spec, x0), f.dim, (*f.spec)->path, true,
            [c, x0](double x, DrawState& d) { d.channel_factor[c] *= x0 / x; });
      }
  }
  for (const Factor& f : factors) {
    if (!*f.spec || !f.shared) continue;
    std::vector<std::tuple<std::size_t, double, double>> channels;  // (c, x0_c, σ_c)
    for (std::size_t c = 0; c < m.channels.size(); ++c)
      if (const auto& b = m.channels[c].bridge)
        channels.emplace_back(c, (*b).*f.value, absolute(**f.spec, (*b).*f.value));
    if (channels.empty()) continue;
    const auto [c0, x00, s00] = channels.front();
    in.add(std::string(f.words) + " of every channel (one draw)", x00, s00, f.dim, (*f.spec)->path,
           true, [channels, x00, s00](double x, DrawState& d) {
             const double z = s00 > 0 ? (x - x00) / s00 : 0.0;
             for (const auto& [c, x0, sigma] : channels) {
               const double xc = x0 + sigma * z;
               if (!(xc > 0)) throw std::domain_error("a shared bridge factor drawn <= 0");
               d.channel_factor[c] *= x0 / xc;
             }
           });
  }
}

// One bar's material and geometry.
void add_bar_inputs(InputList& in, const BarUncertainty& b, const BarSpec& bar) {
  const std::string of = " of bar " + bar.name;
  const std::size_t i = b.bar;
  if (b.youngs_modulus)
    in.add("Young's modulus" + of, bar.material.youngs_modulus_Pa,
           absolute(*b.youngs_modulus, bar.material.youngs_modulus_Pa), Dimension::kPressure,
           b.youngs_modulus->path, true,
           [i](double x, DrawState& d) { set_instantaneous_modulus(d.scene.bars[i].material, x); });
  if (b.density)
    in.add("density" + of, bar.material.density_kg_m3,
           absolute(*b.density, bar.material.density_kg_m3), Dimension::kDensity, b.density->path,
           true, [i](double x, DrawState& d) { d.scene.bars[i].material.density_kg_m3 = x; });
  if (b.wave_speed) {
    // c0 = sqrt(E/ρ): the drawn speed with the drawn density sets the modulus when the density
    // is the other uncertain value, else with the (drawn) modulus the density. Applied after
    // the bar's modulus and density (inputs are applied in order).
    const double c0 = bar.material.wave_speed_m_s();
    const bool keep_density = b.density && !b.youngs_modulus;
    in.add("wave speed" + of, c0, absolute(*b.wave_speed, c0), Dimension::kVelocity,
           b.wave_speed->path, true, [i, keep_density](double x, DrawState& d) {
             MaterialSpec& mat = d.scene.bars[i].material;
             if (keep_density)
               set_instantaneous_modulus(mat, mat.density_kg_m3 * x * x);
             else
               mat.density_kg_m3 = mat.youngs_modulus_Pa / (x * x);
           });
  }
  if (b.poisson_ratio) {
    const double nu = bar.material.poisson_ratio;
    const double sigma = absolute(*b.poisson_ratio, nu);
    const double step = kPoissonGridSigma * sigma;
    in.add("Poisson's ratio" + of, nu, sigma, Dimension::kDimensionless, b.poisson_ratio->path,
           true, [i, nu, step](double x, DrawState& d) {
             d.scene.bars[i].material.poisson_ratio = nu + step * std::round((x - nu) / step);
           });
  }
  if (b.diameter)
    in.add("diameter" + of, bar.diameter_m, absolute(*b.diameter, bar.diameter_m),
           Dimension::kLength, b.diameter->path, true,
           [i](double x, DrawState& d) { set_bar_diameter(d.scene.bars[i], x); });
  if (b.length)
    in.add("length" + of, bar.length_m, absolute(*b.length, bar.length_m), Dimension::kLength,
           b.length->path, true, [i](double x, DrawState& d) { d.scene.bars[i].length_m = x; });
}

// The incident and transmitted gauges' distances to the specimen.
void add_gauge_position_inputs(InputList& in, const StandardUncertainty& position,
                               const Scene& scene, const KolskySetup& setup) {
  const std::size_t s = *scene.specimen;
  for (const auto& [bar, gauge, distance] :
       {std::tuple{s - 1, setup.incident_gauge, setup.incident_distance_m},
        std::tuple{s + 1, setup.transmitted_gauge, setup.transmitted_distance_m}}) {
    const auto& gauges = scene.bars[bar].gauges;
    const auto g =
        static_cast<std::size_t>(std::find_if(gauges.begin(), gauges.end(),
                                              [&](const GaugeSpec& x) { return x.name == gauge; }) -
                                 gauges.begin());
    // Drawn as the distance to the specimen; moved along the bar by the difference.
    in.add("distance of gauge " + gauge + " to the specimen", distance,
           absolute(position, distance), Dimension::kLength, position.path, true,
           [bar, g, distance, toward = bar < s](double x, DrawState& d) {
             d.scene.bars[bar].gauges[g].position_m += (toward ? -1 : 1) * (x - distance);
           });
  }
}

// A time shift drawn beyond the record moves its pulse off it, onto samples the record does not
// hold: its draws must stay within the record's span as a positive value's keep their sign
// (kSignKeepingSigmas standard deviations: beyond, with probability below 1e-9 per draw).
void require_shift_within_record(const std::string& file, const std::string& path,
                                 const std::string& given, double sigma_s,
                                 const GaugeSignals& signals) {
  const double span = signals.time_s.back() - signals.time_s.front();
  if (sigma_s < span / kSignKeepingSigmas) return;
  char what[300];
  std::snprintf(what, sizeof what,
                "a time shift of standard deviation %s would move its pulse off the record "
                "(%s long); expected one below %s (the record / %g)",
                JsonValue::format(sigma_s, Dimension::kTime).c_str(),
                JsonValue::format(span, Dimension::kTime).c_str(),
                JsonValue::format(span / kSignKeepingSigmas, Dimension::kTime).c_str(),
                kSignKeepingSigmas);
  throw input_error(file, path, given, what);
}

// Timing (trigger delay, window starts), the dispersion cut-off and the friction coefficient.
void add_analysis_inputs(InputList& in, const Scene& scene, const UncertaintySpec& u,
                         const GaugeSignals& signals, const ProcessingOptions& options,
                         const KolskySetup& setup) {
  const std::string file = scene.file.string();
  if (u.trigger_delay)
    require_shift_within_record(file, u.trigger_delay->path,
                                JsonValue::format(u.trigger_delay->value, Dimension::kTime),
                                u.trigger_delay->value, signals);
  if (u.window_start)
    require_shift_within_record(file, u.window_start->path,
                                format_double(u.window_start->value) + " samples",
                                u.window_start->value * signals.dt_s, signals);
  if (u.trigger_delay)
    in.add("trigger delay of the transmitted record", 0, u.trigger_delay->value, Dimension::kTime,
           u.trigger_delay->path, false,
           [](double x, DrawState& d) { d.options.transmitted_shift_s += x; });
  if (u.window_start) {
    const double dt = signals.dt_s;
    in.add("start of the reflected window", 0, u.window_start->value * dt, Dimension::kTime,
           u.window_start->path, false,
           [](double x, DrawState& d) { d.options.reflected_shift_s += x; });
    in.add("start of the transmitted window", 0, u.window_start->value * dt, Dimension::kTime,
           u.window_start->path, false,
           [](double x, DrawState& d) { d.options.transmitted_shift_s += x; });
  }
  if (u.dispersion_cutoff && !options.dispersion.correction)
    throw input_error(scene.file.string(), u.dispersion_cutoff->path, "",
                      "the reduction applies no dispersion correction (measurement.dispersion "
                      "\"correction\": \"none\", or simulated signals): it has no cut-off");
  if (u.dispersion_cutoff) {
    const double f0 =
        dispersion_cutoff_Hz(options.dispersion, setup.front_waveguide);  // the reduction's
    in.add("dispersion cut-off frequency", f0, absolute(*u.dispersion_cutoff, f0),
           Dimension::kFrequency, u.dispersion_cutoff->path, true, [f0](double x, DrawState& d) {
             // The cut-off scales with its draw whichever way the scene gives it (f·a/c0 ∝ f).
             DispersionSpec& ds = d.options.dispersion;
             if (ds.cutoff_Hz)
               *ds.cutoff_Hz *= x / f0;
             else
               ds.cutoff_fa_c0 = ds.cutoff_fa_c0.value_or(kDefaultCutoffFaOverC0) * x / f0;
           });
  }
  if (u.friction) {
    const double mu = *scene.measurement->corrections.friction;
    // μ ≥ 0: a draw below zero is the frictionless face.
    in.add("friction coefficient of the specimen faces", mu, absolute(*u.friction, mu),
           Dimension::kDimensionless, u.friction->path, false, [](double x, DrawState& d) {
             d.scene.measurement->corrections.friction = std::max(0.0, x);
           });
  }
}

}  // namespace

std::vector<Input> inputs_of(const Scene& scene, const MeasurementSpec& m,
                             const GaugeSignals& signals, const ProcessingOptions& options,
                             const KolskySetup& setup) {
  const UncertaintySpec& u = *scene.measurement->uncertainty;
  InputList in;
  in.file = scene.file.string();
  add_bridge_inputs(in, u, m);
  for (const BarUncertainty& b : u.bars) add_bar_inputs(in, b, scene.bars[b.bar]);
  if (u.gauge_position) add_gauge_position_inputs(in, *u.gauge_position, scene, setup);
  add_analysis_inputs(in, scene, u, signals, options, setup);
  return std::move(in.in);
}

}  // namespace shpb
