#include "study/reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/record_filter.hpp"
#include "model/wave_travel.hpp"
#include "study/sweep.hpp"

namespace shpb {

namespace {
// Same material and area: relative difference of impedance, wave speed and area below this.
constexpr double kSameBar = 1e-9;

bool same(double a, double b) {
  return std::abs(a - b) <= kSameBar * std::max(std::abs(a), std::abs(b));
}
}  // namespace

std::optional<GaugeReference> exact_reference(const Scene& scene) {
  if (scene.bars.size() != 2) return std::nullopt;
  const BarSpec& s = scene.bars[0];
  const BarSpec& b = scene.bars[1];
  if (!s.material.is_elastic() || !b.material.is_elastic() || !s.gauges.empty() ||
      b.gauges.empty() || s.velocity_m_s <= 0 || b.velocity_m_s != 0 ||
      !same(s.material.youngs_modulus_Pa, b.material.youngs_modulus_Pa) ||
      !same(s.material.density_kg_m3, b.material.density_kg_m3) || !same(s.area_m2, b.area_m2))
    return std::nullopt;
  const double c0 = s.material.wave_speed_m_s();
  const double V = s.velocity_m_s, duration = striker_pulse_s(scene, 0);
  std::vector<double> positions;
  double first_reflection = std::numeric_limits<double>::infinity();
  for (const GaugeSpec& g : b.gauges) {
    positions.push_back(g.position_m);
    first_reflection = std::min(first_reflection, (2 * b.length_m - g.position_m) / c0);
  }
  GaugeReference r;
  r.exact = true;
  r.description =
      "exact: striker on a bar of the same impedance (docs/methods.md §4), square strain pulse "
      "-V/(2 c0) lasting 2 L_s/c0 at each gauge, compared until the far-end reflection arrives";
  r.window_end_s = first_reflection;
  // Time zero is first contact (docs/outputs.md (conventions)); the pulse front reaches a gauge at
  // x/c0.
  r.strain = [positions, c0, V, duration](std::size_t column, double t) {
    const double arrival = positions[column] / c0;
    return t >= arrival && t < arrival + duration ? -V / (2 * c0) : 0.0;
  };
  // The square pulse convolved with a Gaussian: a difference of two normal distribution functions.
  r.recorded = [positions, c0, V, duration](std::size_t column, double t, double sigma_s) {
    const double arrival = positions[column] / c0;
    const auto phi = [sigma_s](double x) {
      return 0.5 * std::erfc(-x / (std::sqrt(2.0) * sigma_s));
    };
    return -V / (2 * c0) * (phi(t - arrival) - phi(t - arrival - duration));
  };
  return r;
}

ParetoCase fine_reference_case(double resolution) {
  return {ContactMethod::kLocalizedBipenalty, Stepping::kAsynchronous, resolution};
}

namespace {
bool coarser_specimen(const Scene& scene, double resolution) {
  return scene.specimen && resolution > kReferenceSpecimenResolution;
}
}  // namespace

Scene fine_reference_scene(const Scene& scene, double resolution) {
  Scene fine = scene_for(scene, fine_reference_case(resolution));
  if (coarser_specimen(scene, resolution)) {
    const std::size_t s = *scene.specimen;
    fine.bars[s].elements =
        scene_at_resolution(scene, kReferenceSpecimenResolution).bars[s].elements;
  }
  fine.simulation.sample_rate_Hz *= kReferenceOversampling;
  return fine;
}

GaugeReference fine_mesh_reference(const Scene& scene, double resolution, bool stable,
                                   const std::string& failure, TimeSeries gauges,
                                   double wall_time_s) {
  GaugeReference r;
  r.description = "fine-mesh run: localized-bipenalty, asynchronous, " + format_factor(resolution) +
                  " x the automatic mesh" +
                  (coarser_specimen(scene, resolution)
                       ? " (the specimen " + format_factor(kReferenceSpecimenResolution) + " x)"
                       : std::string()) +
                  " (the scene has no exact solution)";
  if (!stable) r.description += "; WARNING: the reference run was unstable: " + failure;
  r.window_end_s = std::numeric_limits<double>::infinity();
  r.fine.columns = r.recorded_fine.columns = gauges.columns;
  for (std::size_t k = 0; k < gauges.samples(); k += kReferenceOversampling)
    r.fine.time_s.push_back(gauges.time_s[k]);
  r.recorded_fine.time_s = r.fine.time_s;
  for (const std::vector<double>& v : gauges.values) {
    std::vector<double> points;
    for (std::size_t k = 0; k < v.size(); k += kReferenceOversampling) points.push_back(v[k]);
    r.fine.values.push_back(std::move(points));
    r.recorded_fine.values.push_back(
        record_smoothed(v, kReferenceOversampling, kReferenceOversampling));
  }
  r.wall_time_s = wall_time_s;
  return r;
}

GaugeReference fine_mesh_reference(const Scene& scene, double resolution,
                                   const SimulationOptions& options) {
  SimulationResult run = simulate(fine_reference_scene(scene, resolution), options);
  return fine_mesh_reference(scene, resolution, run.stable, run.failure, std::move(run.gauges),
                             run.wall_time_s);
}

double gauge_error(const TimeSeries& gauges, const GaugeReference& reference) {
  double diff = 0, norm = 0;
  const std::size_t n = gauges.samples();
  const std::size_t columns = gauges.values.size();
  if (!reference.exact &&
      (reference.fine.samples() == 0 || reference.fine.values.size() != columns))
    return std::numeric_limits<double>::quiet_NaN();
  std::size_t compared = 0;
  const std::size_t window =
      reference.exact ? std::numeric_limits<std::size_t>::max() : reference.fine.samples();
  for (std::size_t k = 0; k < std::min(n, window); ++k) {
    const double t = gauges.time_s[k];
    if (!(t < reference.window_end_s)) break;
    for (std::size_t c = 0; c < columns; ++c) {
      const double ref = reference.exact ? reference.strain(c, t) : reference.fine.values[c][k];
      const double d = gauges.values[c][k] - ref;
      diff += d * d;
      norm += ref * ref;
    }
    ++compared;
  }
  if ((!reference.exact && compared != reference.fine.samples()) || norm <= 0)
    return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(diff / norm);
}

}  // namespace shpb
