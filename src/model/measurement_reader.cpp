#include "model/measurement_reader.hpp"

#include <algorithm>

#include "core/closest_match.hpp"
#include "model/input_keys.hpp"
#include "model/uncertainty_reader.hpp"

namespace shpb {
namespace {

ColumnRef read_column(const JsonValue& v) {
  ColumnRef c;
  if (v.is_string())
    c.name = v.header_name();
  else if (v.is_number())
    c.index = static_cast<int>(v.integer(0, 100000));
  else
    throw v.error("expected a column name (string) or a 0-based column index (integer)");
  return c;
}

// measurement.time.interval (or rate) and start: the time base of a file without a time column,
// whose every column is then a channel. With a time column, its unit or its resampling it would say
// two things about the clock: refused. The interval is held to a digitizer's range
// (kMinSampleInterval_s … kMaxSampleInterval_s, as a time column's), the rate to its inverse.
std::optional<SampleClock> read_sample_clock(const JsonObject& to) {
  const auto interval = to.get("interval"), rate = to.get("rate"), start = to.get("start");
  if (!interval && !rate) {
    if (start) throw start->error("a start needs measurement.time.interval (or rate)");
    return std::nullopt;
  }
  if (interval && rate) throw rate->error("give the sample interval or the sample rate, not both");
  const JsonValue& given = interval ? *interval : *rate;
  for (const char* key : {"column", "unit", "resample"})
    if (to.get(key))
      throw given.error(std::string("a time base for a file without a time column; not with "
                                    "measurement.time.") +
                        key + " (which are of a time column)");
  SampleClock c;
  c.interval_s = interval ? interval->quantity_in(Dimension::kTime, kMinSampleInterval_s,
                                                  kMaxSampleInterval_s, false, false)
                          : 1 / rate->quantity_in(Dimension::kFrequency, 1 / kMaxSampleInterval_s,
                                                  1 / kMinSampleInterval_s, false, false);
  if (start) c.start_s = start->quantity(Dimension::kTime);
  return c;
}

BridgeSpec read_bridge(const JsonValue& v) {
  const auto o = v.object(input_keys::kBridge);
  BridgeSpec b;
  const auto arms = o.require("arms", "active arms of the Wheatstone bridge: 1, 2 or 4");
  b.arms = static_cast<int>(arms.integer(1, 4));
  if (b.arms == 3) throw arms.error("must be 1 (quarter bridge), 2 (half) or 4 (full)");
  b.gauge_factor =
      o.require("gauge_factor", "e.g. 2.06").positive_quantity(Dimension::kDimensionless);
  b.excitation_V = o.require("excitation", "e.g. \"8 V\"").positive_quantity(Dimension::kVoltage);
  if (auto g = o.get("gain")) b.gain = g->positive_quantity(Dimension::kDimensionless);
  return b;
}

TimeWindow read_window(const JsonValue& v) {
  const auto items = v.array();
  if (items.size() != 2) throw v.error("expected [start, end], e.g. [\"20 us\", \"120 us\"]");
  TimeWindow w{items[0].quantity(Dimension::kTime), items[1].quantity(Dimension::kTime)};
  if (!(w.end_s > w.start_s)) throw v.error("the end must come after the start");
  return w;
}

// {"strain": [from, to]} (engineering strain, 0 ≤ from < to) or {"time": [from, to]} (times).
RateWindow read_rate_window(const JsonValue& v) {
  const auto o = v.object(input_keys::kRateWindow);
  const auto strain = o.get("strain"), time = o.get("time");
  if (strain.has_value() == time.has_value())
    throw v.error(
        "expected {\"strain\": [from, to]} or {\"time\": [from, to]}, e.g. {\"strain\": "
        "[0.05, 0.2]}");
  RateWindow w;
  w.by_strain = strain.has_value();
  const JsonValue& range = strain ? *strain : *time;
  const auto items = range.array();
  if (items.size() != 2)
    throw range.error(strain ? "expected [from, to], e.g. [0.05, 0.2]"
                             : "expected [from, to], e.g. [\"260 us\", \"300 us\"]");
  if (w.by_strain) {
    w.from = items[0].quantity_in(Dimension::kDimensionless, 0, 1, false, true);
    w.to = items[1].quantity_in(Dimension::kDimensionless, 0, 1, false, true);
  } else {
    w.from = items[0].quantity(Dimension::kTime);
    w.to = items[1].quantity(Dimension::kTime);
  }
  if (!(w.to > w.from)) throw range.error("the end must come after the start");
  return w;
}

// A channel's full scale: ±value or [low, high], a voltage for a channel in volts (kept in the
// column's unit), a number in the column's unit otherwise.
std::array<double, 2> read_channel_range(const JsonValue& v, SignalUnit unit) {
  const bool volts = unit == SignalUnit::kVolt || unit == SignalUnit::kMillivolt;
  const Dimension d = volts ? Dimension::kVoltage : Dimension::kDimensionless;
  const double per = unit == SignalUnit::kMillivolt ? 1e3 : 1.0;  // column units per volt
  const char* expected = volts ? "expected the channel's full scale, \"5 V\" (±5 V) or "
                                 "[\"-1 V\", \"9 V\"]"
                               : "expected the channel's full scale in its unit, 5000 (±5000) or "
                                 "[-1000, 9000]";
  if (v.is_string() || v.is_number()) {
    const double half = v.quantity(d) * per;
    if (!(half > 0)) throw v.error(expected);
    return {-half, half};
  }
  const auto ends = v.array();
  if (ends.size() != 2) throw v.error(expected);
  const std::array<double, 2> r{ends[0].quantity(d) * per, ends[1].quantity(d) * per};
  if (!(r[1] > r[0])) throw v.error("the high end must exceed the low one");
  return r;
}

ChannelSpec read_channel(const JsonValue& v, const std::filesystem::path& scene_dir,
                         const std::vector<std::string>& gauges) {
  const auto o = v.object(input_keys::kChannel);
  ChannelSpec c;
  const auto gauge = o.require("gauge", "the name of a gauge in bars[].gauges");
  c.gauge = gauge.string();
  bool known = false;
  for (const auto& g : gauges) known = known || g == c.gauge;
  if (!known)
    throw gauge.error(gauges.empty() ? "the scene has no gauges"
                                     : "no such gauge; " + suggestion_text(c.gauge, gauges));
  if (auto f = o.get("file")) c.file = (scene_dir / f->name()).lexically_normal();
  if (auto col = o.get("column")) c.column = read_column(*col);
  const auto unit = o.require("unit", "\"V\", \"mV\", \"strain\" or \"microstrain\"");
  c.unit = enum_from(unit, kSignalUnitNames);
  const bool volts = c.unit == SignalUnit::kVolt || c.unit == SignalUnit::kMillivolt;
  if (auto sc = o.get("scale")) {
    if (!volts)
      throw sc->error(
          "a scale (strain per volt) converts volts; it applies only to \"unit\": \"V\" or "
          "\"mV\"");
    if (o.get("bridge")) throw sc->error("give either scale (strain per volt) or bridge, not both");
    c.scale = sc->quantity(Dimension::kDimensionless);
    if (!(*c.scale != 0)) throw sc->error("expected a non-zero strain per volt, e.g. 1.2e-3");
  }
  if (auto b = o.get("bridge")) {
    if (!volts)
      throw b->error("a bridge converts volts; it applies only to \"unit\": \"V\" or \"mV\"");
    c.bridge = read_bridge(*b);
  } else if (volts && !c.scale) {
    throw input_error(v.file(), json_child_path(v.path(), "bridge"), "(missing)",
                      "required for \"unit\": \"" + unit.string() +
                          "\": {\"arms\", \"gauge_factor\", \"excitation\", "
                          "\"gain\"} (or \"scale\": strain per volt)");
  }
  if (auto i = o.get("invert")) c.invert = i->boolean();
  if (auto r = o.get("range")) c.range = read_channel_range(*r, c.unit);
  return c;
}

DispersionSpec read_dispersion(const JsonValue& v) {
  const auto o = v.object(input_keys::kDispersion);
  DispersionSpec d;
  if (auto c = o.get("correction")) d.correction = enum_from(*c, kCorrectionNames);
  if (auto a = o.get("amplitude_factors")) d.amplitude_factors = a->boolean();
  // A frequency with its unit, or the dimensionless f·a/c0 under its own key: a bare number
  // would have two meanings (0.2619 as f·a/c0 is 0.26 Hz as a frequency).
  if (auto c = o.get("cutoff")) {
    if (!c->is_string())
      throw c->error(
          "a bare number is ambiguous: give a frequency with its unit (\"250 kHz\") "
          "or the dimensionless f·a/c0 as cutoff_fa_c0 (e.g. 0.2619)");
    d.cutoff_Hz = c->positive_quantity(Dimension::kFrequency);
  }
  if (auto c = o.get("cutoff_fa_c0")) {
    if (d.cutoff_Hz) throw c->error("give cutoff (a frequency) or cutoff_fa_c0, not both");
    d.cutoff_fa_c0 = c->quantity_in(Dimension::kDimensionless, 0, 10, true, false);
  }
  return d;
}

// An uncertainty of a bridge factor with no bridge to apply it to would be propagated as zero.
void require_bridge(const JsonValue& measurement, const MeasurementSpec& m, bool bridged) {
  if (!m.uncertainty || bridged) return;
  const UncertaintySpec& u = *m.uncertainty;
  const nlohmann::json& given = measurement.json()["uncertainty"];
  for (const auto& [key, spec] :
       {std::pair{"gauge_factor", &u.gauge_factor}, std::pair{"excitation", &u.excitation},
        std::pair{"gain", &u.gain}})
    if (*spec)
      throw input_error(measurement.file(), (*spec)->path, given[key].dump(),
                        "a bridge's uncertainty needs measured channels in volts with a bridge");
}

}  // namespace

MeasurementSpec read_measurement(const JsonValue& value, const std::filesystem::path& scene_dir,
                                 const std::vector<std::string>& gauges,
                                 const std::vector<std::string>& bars,
                                 std::optional<std::size_t> specimen) {
  const auto o = value.object(input_keys::kMeasurement);
  MeasurementSpec m;
  const auto uncertainty = o.get("uncertainty");
  if (uncertainty) m.uncertainty = read_uncertainty(*uncertainty, bars, specimen);
  // The reduction's choices, which also apply to `process --signals` of simulated gauges.
  if (auto t = o.get("test"))
    m.tension = enum_from<bool>(*t, {{"compression", false}, {"tension", true}});
  if (auto d = o.get("load_drop")) {
    if (d->json().is_boolean()) {
      if (d->boolean())
        throw d->error("false (cut at the strain maximum only) or a fraction, e.g. 0.5");
      m.load_drop = 0.0;
    } else {
      m.load_drop = d->quantity_in(Dimension::kDimensionless, 0, 1, true, true);
    }
  }
  if (auto a = o.get("align")) m.align = enum_from(*a, kAlignmentNames);
  if (auto p = o.get("primary")) m.primary = enum_from(*p, kPrimaryNames);
  if (auto w = o.get("rate_window")) m.rate_window = read_rate_window(*w);
  if (auto c = o.get("corrections")) {
    const auto co = c->object(input_keys::kCorrections);
    // Coulomb coefficient of the faces, as contact.friction (docs/methods.md §8).
    if (auto f = co.get("friction"))
      m.corrections.friction = f->quantity_in(Dimension::kDimensionless, 0, 1, false, true);
    if (auto i = co.get("inertia")) m.corrections.inertia = i->boolean();
    // Closed forms of a compression specimen that widens between sliding faces (docs/methods.md
    // §8): a tension specimen is bonded to its bars and narrows.
    if (m.tension && (m.corrections.friction || m.corrections.inertia))
      throw(m.corrections.friction ? *co.get("friction") : *co.get("inertia"))
          .error(
              "the friction and inertia corrections are those of a compression specimen "
              "(docs/methods.md §8), not of a bonded tension specimen: drop them for "
              "\"test\": \"tension\"");
  }
  // An uncertainty of a value the scene does not use would be propagated as zero: refused.
  if (uncertainty && m.uncertainty->friction && !m.corrections.friction)
    throw input_error(value.file(), m.uncertainty->friction->path,
                      uncertainty->json()["friction"].dump(),
                      "an uncertainty of the friction correction's coefficient needs "
                      "measurement.corrections.friction");

  // Corrections or the reduction's choices alone (for `process --signals` of simulated gauges):
  // no signals to read, so no key of the record (read by nothing then).
  if (!o.get("channels") && !o.get("file") &&
      (o.get("test") || o.get("load_drop") || o.get("corrections") || o.get("align") ||
       o.get("primary") || o.get("rate_window") || uncertainty)) {
    for (const char* key :
         {"format", "time", "sheet", "dispersion", "windows", "reflected_time", "striker_velocity"})
      if (auto k = o.get(key))
        throw k->error(
            "a key of the measured record, which this measurement has none of (no channels): "
            "process --signals of simulated gauges reads only the reduction's choices (test, "
            "load_drop, corrections, align, primary, rate_window) and their uncertainty");
    require_bridge(value, m, false);
    return m;
  }
  if (auto f = o.get("file")) m.file = (scene_dir / f->name()).lexically_normal();
  if (auto f = o.get("format")) m.format = enum_from(*f, kSignalFormatNames);
  if (auto t = o.get("time")) {
    const auto to = t->object(input_keys::kMeasurementTime);
    m.time_clock = read_sample_clock(to);
    if (auto c = to.get("column")) m.time_column = read_column(*c);
    if (auto r = to.get("resample")) {
      if (r->json().is_boolean()) {
        m.time_resample.mode = r->boolean() ? TimeResample::kAlways : TimeResample::kNever;
      } else if (r->is_string()) {
        m.time_resample.mode = TimeResample::kAlways;
        m.time_resample.interval_s = r->positive_quantity(Dimension::kTime);
      } else {
        throw r->error(
            "true (resample onto the mean interval), false (refuse a non-uniform time base) or "
            "an interval, e.g. \"1 us\"");
      }
    }
    if (auto u = to.get("unit")) {
      const std::string unit = u->string();
      // "1 " + "" would parse as a bare number, silently seconds.
      if (unit.find_first_not_of(" \t") == std::string::npos)
        throw u->error("expected a time unit such as \"us\"");
      try {
        m.time_unit_s = parse_quantity("1 " + unit, Dimension::kTime);
        m.time_unit = unit;
      } catch (const std::invalid_argument& e) {
        throw u->error(e.what());
      }
    }
  }
  const auto channels = o.require("channels", "a list of {\"gauge\", \"column\", \"unit\", ...}");
  for (const auto& ch : channels.array()) m.channels.push_back(read_channel(ch, scene_dir, gauges));
  if (m.channels.empty()) throw channels.error("must list at least one channel");
  for (std::size_t i = 0; i < m.channels.size(); ++i)
    if (m.file.empty() && m.channels[i].file.empty())
      throw input_error(value.file(), json_child_path(channels.array()[i].path(), "file"),
                        "(missing)", "required: the channel's file, or measurement.file for all");
  if (auto d = o.get("dispersion")) m.dispersion = read_dispersion(*d);
  if (auto w = o.get("windows")) {
    const auto wo = w->object(input_keys::kWindows);
    if (auto x = wo.get("incident")) m.windows.incident = read_window(*x);
    if (auto x = wo.get("reflected")) m.windows.reflected = read_window(*x);
    if (auto x = wo.get("transmitted")) m.windows.transmitted = read_window(*x);
  }
  if (auto sh = o.get("sheet")) m.sheet = sh->name();
  if (auto r = o.get("reflected_time")) m.reflected_time_s = r->positive_quantity(Dimension::kTime);
  if (auto s = o.get("striker_velocity"))
    m.striker_velocity_m_s = s->positive_quantity(Dimension::kVelocity);
  require_bridge(value, m,
                 std::any_of(m.channels.begin(), m.channels.end(),
                             [](const ChannelSpec& c) { return c.bridge.has_value(); }));
  return m;
}

}  // namespace shpb
