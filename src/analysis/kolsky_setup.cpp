#include "analysis/kolsky_setup.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/message_text.hpp"
#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"
#include "dispersion/pochhammer_chree.hpp"  // the supported Poisson ratios
#include "model/computable.hpp"
#include "model/scene_inputs.hpp"
#include "model/test_setup.hpp"

namespace shpb {
namespace {

BarSide side_of(const BarSpec& b) {
  return {b.material.youngs_modulus_Pa, b.area_m2, b.material.wave_speed_m_s()};
}
BarWaveguide waveguide_of(const BarSpec& b) {
  BarWaveguide w{0.5 * b.diameter_m, b.material.wave_speed_m_s(), b.material.poisson_ratio};
  if (b.material.model == MaterialModel::kViscoelastic) {  // a polymer bar (methods.md §5.1)
    const double e0 = b.material.youngs_modulus_Pa;
    w.long_term_fraction = b.material.viscoelastic.long_term_modulus_Pa / e0;
    for (const MaxwellArm& a : b.material.viscoelastic.arms)
      w.arms.push_back({a.modulus_Pa / e0, a.relaxation_time_s});
  }
  return w;
}

// A striker this much stiffer than the bar has its pulse's level taken over the first step: each
// later step is q = (Z_s − Z_b)/(Z_s + Z_b) ≥ 1/3 of the one before, and from q = 1/2 on the second
// passes plateau_level's half-height and enters the level. A ratio far from 1 keeps the
// uncertainty draws of a striker of the bar's own impedance on one side of the rule.
constexpr double kStaircaseImpedanceRatio = 2.0;

}  // namespace

double transmitted_arrival_s(const KolskySetup& setup, double incident_s) {
  return incident_s + setup.incident_distance_m / setup.front.c0_m_s + setup.specimen_transit_s +
         setup.transmitted_distance_m / setup.back.c0_m_s;
}

double striker_velocity_from_plateau(const KolskySetup& setup, double incident_plateau_strain) {
  const double z_b = setup.incident_impedance_kg_s;
  const double z_s = setup.striker_impedance_kg_s.value_or(z_b);
  return setup.front.c0_m_s * incident_plateau_strain * (z_s + z_b) / z_s;
}

std::size_t first_step_end(const KolskySetup& setup, std::size_t onset, std::size_t end,
                           double dt) {
  if (!setup.striker_staircase) return end;
  return std::min(end,
                  onset + static_cast<std::size_t>(std::ceil(*setup.striker_round_trip_s / dt)));
}

double struck_end_plateau(const KolskySetup& setup, std::span<const double> record, double dt,
                          const PulseWindow& w) {
  if (!setup.front_waveguide.viscoelastic())
    return plateau_level(record, w.onset, first_step_end(setup, w.onset, w.end, dt), w.sign);
  // Moved back by the gauge's distance, the pulse starts that much earlier: the record is put
  // behind as many samples at rest, so that it keeps its window.
  const double distance = setup.incident_gauge_position_m;
  const auto lead = static_cast<std::size_t>(std::ceil(distance / (setup.front.c0_m_s * dt)));
  std::vector<double> padded(lead + record.size(), 0.0);
  std::copy(record.begin(), record.end(), padded.begin() + static_cast<std::ptrdiff_t>(lead));
  PropagationOptions o;
  o.dispersion = false;
  o.quantity = WaveQuantity::kVelocity;
  o.law_cutoff_Hz = law_band_limit_Hz(setup.front_waveguide, distance);
  const auto moved = Propagator(setup.front_waveguide, o).propagate(padded, dt, -distance);
  // At the struck end the pulse is the striker's, shorter than the gauge's window, which holds the
  // law's creep tail too: its level is taken over the pulse found there.
  Baseline rest;
  rest.noise = estimate_baseline(record).noise;
  const std::span<const double> head(moved.data(), std::min(w.end, moved.size()));
  const auto pulse = find_first_pulse(head, rest, w.onset);
  const std::size_t onset = pulse ? pulse->onset : w.onset, end = pulse ? pulse->end : w.end;
  return plateau_level(moved, onset, first_step_end(setup, onset, end, dt), w.sign);
}

KolskySetup resolve_setup(const Scene& scene, const std::vector<std::string>& available) {
  const std::string file = scene.file.string();
  if (!scene.specimen)
    throw input_error(file, "specimen", "missing", "processing needs the specimen bar named");
  const std::size_t s = *scene.specimen;
  if (s == 0 || s + 1 >= scene.bars.size())
    throw input_error(file, "specimen", scene.bars[s].name,
                      "needs a bar on each side (incident and transmitter)");
  check_reduction_computable(scene);
  const BarSpec& inc = scene.bars[s - 1];
  const BarSpec& tra = scene.bars[s + 1];
  auto has = [&](const std::string& g) {
    return std::find(available.begin(), available.end(), g) != available.end();
  };
  KolskySetup k;
  for (const auto& g : inc.gauges)
    if (has(g.name)) {
      k.incident_gauge = g.name;
      k.incident_distance_m = *distance_to_specimen_m(scene, s - 1, g.position_m);
      k.incident_gauge_position_m = g.position_m;
      break;
    }
  for (const auto& g : tra.gauges)
    if (has(g.name)) {
      k.transmitted_gauge = g.name;
      k.transmitted_distance_m = *distance_to_specimen_m(scene, s + 1, g.position_m);
      if (s + 2 == scene.bars.size()) k.transmitted_far_end_m = tra.length_m - g.position_m;
      break;
    }
  std::string names;
  for (const auto& a : available) names += (names.empty() ? "" : ", ") + a;
  if (k.incident_gauge.empty())
    throw input_error(file, "bars[" + std::to_string(s - 1) + "].gauges", "\"" + inc.name + "\"",
                      "no gauge of the incident bar has a signal (signals: " + names + ")");
  if (k.transmitted_gauge.empty())
    throw input_error(file, "bars[" + std::to_string(s + 1) + "].gauges", "\"" + tra.name + "\"",
                      "no gauge of the transmitter bar has a signal (signals: " + names + ")");
  k.front = side_of(inc);
  k.back = side_of(tra);
  k.front_waveguide = waveguide_of(inc);
  k.back_waveguide = waveguide_of(tra);
  // Pochhammer–Chree tables are computed for 0 ≤ ν ≤ 0.49 (docs/methods.md §5): bar steels,
  // aluminium, titanium and PMMA lie well inside; auxetic (ν < 0) bars are not supported.
  for (const std::size_t b : {s - 1, s + 1})
    if (const double nu = scene.bars[b].material.poisson_ratio; !poisson_ratio_supported(nu)) {
      const InputLocation at = material_key_location(scene, b, "poisson_ratio");
      throw input_error(at.file, at.path, format_double(nu),
                        "must be in [" + format_double(kMinPoissonRatio) + ", " +
                            format_double(kMaxPoissonRatio) +
                            "] for a bar whose pulses are processed (dispersion "
                            "tables cover that range; auxetic bars are not supported)");
    }
  k.specimen = {scene.bars[s].length_m, scene.bars[s].area_m2};
  if (const double c = scene.bars[s].material.wave_speed_m_s(); c > 0) {
    k.specimen_transit_s = scene.bars[s].length_m / c;
    k.specimen_impedance_kg_s = scene.bars[s].impedance_kg_s();
  }
  k.incident_impedance_kg_s = inc.impedance_kg_s();
  if (scene.measurement && scene.measurement->reflected_time_s) {
    // The model's round trip is 2d/c0; the calibration says how much longer the real bar takes.
    const double modelled = 2 * k.incident_distance_m / k.front.c0_m_s;
    const double calibrated = *scene.measurement->reflected_time_s;
    if (!(std::abs(calibrated - modelled) <= kReflectedTimeRange * modelled))
      throw input_error(
          file, "measurement.reflected_time", fmt("%.6g us", calibrated * 1e6),
          fmt("expected within %.3g %% of the modelled round trip 2d/c0 = %.6g us "
              "(incident gauge %.6g mm from the specimen)",
              100 * kReflectedTimeRange, modelled * 1e6, k.incident_distance_m * 1e3));
    k.excess_delay_s_per_m = (calibrated - modelled) / (2 * k.incident_distance_m);
  }
  const TestRoles roles = test_roles(scene);
  k.pulse_shaper = !roles.shapers.empty();
  if (roles.striker) {
    const BarSpec& striker = scene.bars[*roles.striker];
    k.striker_impedance_kg_s = striker.impedance_kg_s();
    k.striker_round_trip_s = 2 * striker.length_m / striker.material.wave_speed_m_s();
    k.striker_staircase =
        *k.striker_impedance_kg_s >= kStaircaseImpedanceRatio * k.incident_impedance_kg_s;
  }
  k.striker_velocity_m_s = scene_striker_speed_m_s(scene);
  return k;
}

}  // namespace shpb
