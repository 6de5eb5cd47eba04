#include "analysis/specimen_corrections.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/median.hpp"
#include "model/specimen_response.hpp"

namespace shpb {
namespace {
// The loaded part of the curve, over which removed values are summarised.
constexpr double kLoadedFraction = 0.2;

RemovedTerm summarise(std::string name, const std::vector<double>& removed,
                      const std::vector<char>& loaded) {
  std::vector<double> v;
  RemovedTerm t{std::move(name)};
  for (std::size_t i = 0; i < removed.size(); ++i)
    if (loaded[i]) {
      v.push_back(removed[i]);
      t.max_abs_Pa = std::max(t.max_abs_Pa, std::abs(removed[i]));
    }
  t.median_Pa = median(std::move(v));
  return t;
}
}  // namespace

InertiaTerms inertia_terms(const SpecimenProperties& s, double e, double rate, double accel) {
  const double stretch = 1 - e;  // L/L0, compression positive e
  const double L = s.length_m * stretch;
  const double a2 = s.area_m2 / (std::numbers::pi * stretch);  // volume-conserving radius²
  const double rho = s.density_kg_m3;
  InertiaTerms t;
  t.axial_acceleration_Pa = rho * L * L * accel / 12;
  t.axial_convective_Pa = -rho * L * L * rate * rate / 12;
  t.radial_acceleration_Pa = rho * a2 * accel / 8;
  t.radial_convective_Pa = radial_inertia_stress(rho, std::sqrt(a2), rate, 0.0);
  return t;
}

CorrectionReport apply_specimen_corrections(Curve& c, double dt, const SpecimenProperties& s,
                                            const SpecimenCorrections& corrections) {
  CorrectionReport report;
  const std::size_t n = c.strain.size();
  if (n == 0 || (!corrections.friction && !corrections.inertia)) return report;
  const double peak = *std::max_element(c.stress_3wave_Pa.begin(), c.stress_3wave_Pa.end());
  std::vector<char> loaded(n);
  for (std::size_t i = 0; i < n; ++i) loaded[i] = c.stress_3wave_Pa[i] >= kLoadedFraction * peak;

  // True strain rate ε̇ = ė/(1 − e) and its derivative (central differences, one-sided at the ends).
  std::vector<double> rate(n), accel(n);
  for (std::size_t i = 0; i < n; ++i) rate[i] = c.strain_rate_1_s[i] / (1 - c.strain[i]);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i > 0 ? i - 1 : 0, b = std::min(i + 1, n - 1);
    accel[i] = b > a ? (rate[b] - rate[a]) / ((b - a) * dt) : 0.0;
  }
  std::vector<double> axial_acc(n, 0.0), axial_conv(n, 0.0), radial_acc(n, 0.0),
      radial_conv(n, 0.0), friction(n, 0.0);
  report.friction_factor_min = std::numeric_limits<double>::infinity();
  report.friction_factor_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double e = c.strain[i];
    double& s3 = c.stress_3wave_Pa[i];
    if (corrections.inertia) {  // the mean of the two faces' stresses
      const InertiaTerms t = inertia_terms(s, e, rate[i], accel[i]);
      axial_acc[i] = t.axial_acceleration_Pa;
      axial_conv[i] = t.axial_convective_Pa;
      radial_acc[i] = t.radial_acceleration_Pa;
      radial_conv[i] = t.radial_convective_Pa;
      s3 = (s3 * (1 - e) - t.total()) / (1 - e);  // true: force over A0/(1 − e)
    }
    if (corrections.friction) {  // each face's stress, the mean of them as well
      const double length = s.length_m * (1 - e);
      const double diameter = std::sqrt(4 * s.area_m2 / (std::numbers::pi * (1 - e)));
      const double phi = friction_factor(*corrections.friction, diameter, length);
      friction[i] = s3 * (1 - e) - s3 / phi * (1 - e);
      for (std::vector<double>* v : {&c.stress_3wave_Pa, &c.stress_1wave_Pa, &c.stress_2wave_Pa})
        if (i < v->size()) (*v)[i] /= phi;
      if (loaded[i]) {
        report.friction_factor_min = std::min(report.friction_factor_min, phi);
        report.friction_factor_max = std::max(report.friction_factor_max, phi);
      }
    }
    c.true_stress_Pa[i] = s3 * (1 - e);
  }
  if (!corrections.friction) report.friction_factor_min = report.friction_factor_max = 1;
  if (corrections.inertia) {
    report.terms.push_back(summarise("inertia_axial_acceleration", axial_acc, loaded));
    report.terms.push_back(summarise("inertia_axial_convective", axial_conv, loaded));
    report.terms.push_back(summarise("inertia_radial_acceleration", radial_acc, loaded));
    report.terms.push_back(summarise("inertia_radial_convective", radial_conv, loaded));
  }
  if (corrections.friction) report.terms.push_back(summarise("friction", friction, loaded));
  return report;
}

}  // namespace shpb
