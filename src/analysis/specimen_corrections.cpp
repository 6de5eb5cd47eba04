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

// The derivative of a series sampled at dt: central differences, one-sided at the ends.
std::vector<double> derivative(const std::vector<double>& y, double dt) {
  const std::size_t n = y.size();
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i > 0 ? i - 1 : 0, b = std::min(i + 1, n - 1);
    d[i] = b > a ? (y[b] - y[a]) / ((b - a) * dt) : 0.0;
  }
  return d;
}

// A stress, engineering, less a true stress removed at engineering strain e: the true stress is
// the engineering one times (1 − e). A removed 0 leaves it exactly.
void remove_true(double& engineering_Pa, double removed_true_Pa, double e) {
  engineering_Pa -= removed_true_Pa / (1 - e);
}
}  // namespace

InertiaTerms inertia_terms(const SpecimenProperties& s, double e, double rate, double accel,
                           double front_accel, double back_accel) {
  const double stretch = 1 - e;  // L/L0, compression positive e
  const double L = s.length_m * stretch;
  const double a2 = s.area_m2 / (std::numbers::pi * stretch);  // volume-conserving radius²
  const double rho = s.density_kg_m3;
  InertiaTerms t;
  t.axial_acceleration_Pa = rho * L * L * accel / 12;
  t.axial_convective_Pa = -rho * L * L * rate * rate / 12;
  t.front_axial_acceleration_Pa = rho * L * (front_accel / 2 - L * accel / 6);
  t.front_axial_convective_Pa = rho * L * L * rate * rate / 6;
  t.back_axial_acceleration_Pa = -rho * L * (back_accel / 2 + L * accel / 6);
  t.back_axial_convective_Pa = rho * L * L * rate * rate / 6;
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

  // True strain rate ε̇ = ė/(1 − e) and its derivative, the faces' accelerations v̇1 and v̇2.
  std::vector<double> rate(n);
  for (std::size_t i = 0; i < n; ++i) rate[i] = c.strain_rate_1_s[i] / (1 - c.strain[i]);
  const std::vector<double> accel = derivative(rate, dt);
  const std::vector<double> front_accel = derivative(c.velocity_front_m_s, dt);
  const std::vector<double> back_accel = derivative(c.velocity_back_m_s, dt);
  std::vector<double> axial_acc(n, 0.0), axial_conv(n, 0.0), front_acc(n, 0.0), front_conv(n, 0.0),
      back_acc(n, 0.0), back_conv(n, 0.0), radial_acc(n, 0.0), radial_conv(n, 0.0),
      friction(n, 0.0);
  report.friction_factor_min = std::numeric_limits<double>::infinity();
  report.friction_factor_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double e = c.strain[i];
    double& s3 = c.stress_3wave_Pa[i];
    if (corrections.inertia) {  // the mean of the two faces' stresses and each face's
      const InertiaTerms t = inertia_terms(s, e, rate[i], accel[i], front_accel[i], back_accel[i]);
      axial_acc[i] = t.axial_acceleration_Pa;
      axial_conv[i] = t.axial_convective_Pa;
      front_acc[i] = t.front_axial_acceleration_Pa;
      front_conv[i] = t.front_axial_convective_Pa;
      back_acc[i] = t.back_axial_acceleration_Pa;
      back_conv[i] = t.back_axial_convective_Pa;
      radial_acc[i] = t.radial_acceleration_Pa;
      radial_conv[i] = t.radial_convective_Pa;
      remove_true(s3, t.face_average(), e);
      remove_true(c.stress_1wave_Pa[i], t.back_face(), e);
      remove_true(c.stress_2wave_Pa[i], t.front_face(), e);
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
    report.terms.push_back(summarise("inertia_1wave_axial_acceleration", back_acc, loaded));
    report.terms.push_back(summarise("inertia_1wave_axial_convective", back_conv, loaded));
    report.terms.push_back(summarise("inertia_2wave_axial_acceleration", front_acc, loaded));
    report.terms.push_back(summarise("inertia_2wave_axial_convective", front_conv, loaded));
    report.terms.push_back(summarise("inertia_radial_acceleration", radial_acc, loaded));
    report.terms.push_back(summarise("inertia_radial_convective", radial_conv, loaded));
  }
  if (corrections.friction) report.terms.push_back(summarise("friction", friction, loaded));
  return report;
}

}  // namespace shpb
