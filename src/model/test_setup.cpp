#include "model/test_setup.hpp"

#include <cmath>

#include "core/json_value.hpp"

namespace shpb {

namespace {

std::optional<std::size_t> first_moving_bar(const Scene& s) {
  for (std::size_t i = 0; i + 1 < s.bars.size(); ++i)
    if (s.bars[i].velocity_m_s != 0) return i;
  return std::nullopt;
}

// Bars k and k + 1 closing, or a bonded pair without a gap moving apart.
bool interface_loaded(const Scene& s, std::size_t k) {
  const double closing = s.bars[k].velocity_m_s - s.bars[k + 1].velocity_m_s;
  const bool bonded =
      interface_method(s.contact, k) == ContactMethod::kBonded && !(s.bars[k].gap_m > 0);
  return closing > 0 || (closing < 0 && bonded);
}

}  // namespace

TestRoles test_roles(const Scene& s) {
  TestRoles r;
  r.specimen = s.specimen;
  if (s.specimen && *s.specimen > 0) r.incident = *s.specimen - 1;
  if (s.specimen && *s.specimen + 1 < s.bars.size()) r.transmitter = *s.specimen + 1;
  r.striker = first_moving_bar(s);
  if (!r.striker && r.incident && *r.incident > 0) r.striker = 0;
  if (r.striker && r.incident && *r.striker < *r.incident)
    for (std::size_t i = *r.striker + 1; i < *r.incident; ++i) r.shapers.push_back(i);
  return r;
}

std::optional<std::size_t> striker_bar(const Scene& s) {
  const auto i = first_moving_bar(s);
  if (!i) return std::nullopt;
  return interface_loaded(s, *i) ? i : std::nullopt;
}

bool any_interface_loaded(const Scene& s) {
  for (std::size_t k = 0; k + 1 < s.bars.size(); ++k)
    if (interface_loaded(s, k)) return true;
  return false;
}

double bars_between_m(const Scene& s, std::size_t bar) {
  if (!s.specimen) return 0;
  const std::size_t sp = *s.specimen;
  double d = 0;
  for (std::size_t i = bar + 1; i < sp; ++i) d += s.bars[i].length_m;
  for (std::size_t i = sp + 1; i < bar; ++i) d += s.bars[i].length_m;
  return d;
}

std::optional<double> distance_to_specimen_m(const Scene& s, std::size_t bar, double position_m) {
  if (!s.specimen || bar == *s.specimen) return std::nullopt;
  const double own = bar < *s.specimen ? s.bars[bar].length_m - position_m : position_m;
  return own + bars_between_m(s, bar);
}

GaugePlacement place_gauge_at_distance(const Scene& s, std::size_t bar, double d) {
  const double between = bars_between_m(s, bar), length = s.bars[bar].length_m;
  GaugePlacement p;
  if (!(d >= between && d <= between + length))
    p.problem = "must lie on the bar: within [" + JsonValue::format(between, Dimension::kLength) +
                ", " + JsonValue::format(between + length, Dimension::kLength) +
                "] (the pulse's travel in the bars to the specimen face)";
  p.position_m = bar < *s.specimen ? length - (d - between) : d - between;
  return p;
}

std::optional<double> scene_striker_speed_m_s(const Scene& s) {
  if (s.measurement && s.measurement->striker_velocity_m_s)
    return std::abs(*s.measurement->striker_velocity_m_s);
  if (const auto striker = test_roles(s).striker; striker && s.bars[*striker].velocity_m_s != 0)
    return std::abs(s.bars[*striker].velocity_m_s);
  return std::nullopt;
}

double striker_direction(const Scene& s) {
  if (const auto striker = test_roles(s).striker; striker && s.bars[*striker].velocity_m_s != 0)
    return s.bars[*striker].velocity_m_s > 0 ? 1.0 : -1.0;
  return s.measurement && s.measurement->tension ? -1.0 : 1.0;
}

}  // namespace shpb
