#include "model/fit_spec.hpp"

#include <algorithm>
#include <set>

#include "core/closest_match.hpp"
#include "core/json_document.hpp"
#include "core/json_value.hpp"
#include "model/campaign.hpp"
#include "model/input_keys.hpp"
#include "model/law_parameters.hpp"
#include "model/material_reader.hpp"
#include "model/scene.hpp"

namespace shpb {
namespace fs = std::filesystem;

std::string to_string(FitStage s) { return std::string(enum_name(kFitStageNames, s)); }
std::string to_string(FitLoss l) { return std::string(enum_name(kFitLossNames, l)); }
std::string to_string(NuisanceKind k) { return std::string(enum_name(kNuisanceNames, k)); }

Dimension nuisance_dimension(NuisanceKind k) {
  return k == NuisanceKind::kStrikerVelocity || nuisance_is_wave_speed(k) ? Dimension::kVelocity
                                                                          : Dimension::kTime;
}
bool nuisance_is_offset(NuisanceKind k) {
  return k == NuisanceKind::kTimeShift || k == NuisanceKind::kTransmittedDelay;
}
bool nuisance_is_wave_speed(NuisanceKind k) {
  return k == NuisanceKind::kIncidentWaveSpeed || k == NuisanceKind::kTransmitterWaveSpeed;
}

namespace {

// [lo, hi] with lo < hi, each a quantity of dimension d; `alternative` names another form the
// value may take.
std::pair<double, double> read_bounds(const JsonValue& v, Dimension d,
                                      const std::string& alternative = "") {
  if (!v.json().is_array() || v.json().size() != 2)
    throw v.error("expected bounds [lower, upper], each " + quantity_text(d) + alternative);
  const auto items = v.array();
  const double lo = items[0].quantity(d), hi = items[1].quantity(d);
  if (!(lo < hi))
    throw v.error_with_value("[" + JsonValue::format(lo, d) + ", " + JsonValue::format(hi, d) + "]",
                             "the lower bound must be below the upper bound");
  return {lo, hi};
}

// A law with `name` set to `value` must still be a valid material: the material reader says why
// not.
void check_law_accepts(const FitSpec& spec, const std::string& name, double value,
                       const JsonValue& where) {
  nlohmann::json doc = spec.material_document;
  law_parameter_member(doc, name) = value;  // SI, exactly the value tried
  try {
    read_material(JsonValue(doc, spec.material_display, ""), spec.material_display);
  } catch (const InputError& e) {
    throw where.error_with_value(JsonValue::format(value, law_parameter_dimension(name)),
                                 std::string("not a valid value of the law (") + e.what() + ")");
  }
}

}  // namespace

FitSpec read_fit_spec(const Campaign& c) {
  FitSpec spec;
  const JsonValue root(c.document, c.display, "");
  const JsonObject o(root);

  // The starting law.
  const auto material = o.require("material", "the starting material file (the law to fit)");
  if (material.is_string()) {
    const fs::path written = material.string();
    const fs::path file = written.is_absolute() ? written : c.file.parent_path() / written;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
      throw material.error("no such material file (" + file.string() + ")");
    spec.material_display = file.string();
    spec.material_file = file;
    spec.material_document = read_json_object_file(file, spec.material_display);
    spec.material = read_material_document(spec.material_document, spec.material_display);
  } else if (material.is_object()) {
    spec.material_display = c.display;
    spec.material_document = material.json();
    spec.material = read_material(material, "material");
  } else {
    throw material.error("expected a material file name or a material object");
  }

  // Free parameters.
  const auto names = law_parameter_names(spec.material);
  if (auto free = o.get("free")) {
    if (!free->is_object()) throw free->error("expected {\"A\": [lower, upper], ...}");
    for (const auto& [key, value] : free->json().items()) {
      const JsonValue v(value, c.display, json_child_path(free->path(), key));
      if (std::find(names.begin(), names.end(), key) == names.end())
        throw v.error_with_value(json_quoted(key),
                                 "not a parameter of the " +
                                     std::string(to_string(spec.material.model)) + " law; " +
                                     key_suggestion_text(key, names, input_keys::kCampaignPlaces));
      FreeParameter p;
      p.name = key;
      p.json_path = v.path();
      std::tie(p.lower, p.upper) = read_bounds(v, law_parameter_dimension(key));
      p.start = law_parameter(spec.material, key);
      check_law_accepts(spec, key, p.lower, v.array()[0]);
      check_law_accepts(spec, key, p.upper, v.array()[1]);
      if (!(p.start >= p.lower && p.start <= p.upper))
        throw v.error("the starting value " +
                      JsonValue::format(p.start, law_parameter_dimension(key)) + " (" +
                      spec.material_display + ") lies outside the bounds");
      spec.free.push_back(p);
    }
  }

  // Nuisance parameters.
  if (auto nuisance = o.get("nuisance")) {
    const auto n = nuisance->object(input_keys::kNuisance);
    for (const auto& [key, kind] : kNuisanceNames) {
      const auto v = n.get(std::string(key));
      if (!v) continue;
      NuisanceSpec s;
      s.kind = kind;
      s.json_path = v->path();
      if (v->is_string() && !v->string().empty() && v->string().back() == '%') {
        if (nuisance_is_offset(kind))
          throw v->error(
              "a time shift or delay starts at 0: give absolute bounds [\"-2 us\", "
              "\"2 us\"]");
        const double fraction = v->quantity(Dimension::kDimensionless);  // the one "%" parser
        if (!(fraction > 0 && fraction < 1))
          throw v->error("expected \"N %\" with 0 < N < 100 (± N % of each test's start)");
        s.relative = fraction;
      } else {
        s.bounds = read_bounds(*v, nuisance_dimension(kind),
                               nuisance_is_offset(kind) ? "" : "; or \"N %\" of each test's start");
        if (nuisance_is_wave_speed(kind) && !(s.bounds->first > 0))
          throw v->array()[0].error("a wave speed must be > 0");
        if (!nuisance_is_offset(kind) && s.bounds->first < 0)
          throw v->array()[0].error("must be >= 0");
      }
      spec.nuisance.push_back(s);
    }
  }

  // Stages and loss.
  if (auto stages = o.get("stages")) {
    spec.stages.clear();
    const auto items = stages->array();
    if (items.empty())
      throw stages->error(
          "expected a list of the stages to run: " + enum_names_text(kFitStageNames) + " or both");
    for (const auto& item : items) {
      const FitStage st = enum_from(item, kFitStageNames);
      if (std::find(spec.stages.begin(), spec.stages.end(), st) != spec.stages.end())
        throw item.error("stage listed twice");
      spec.stages.push_back(st);
    }
  }
  if (auto loss = o.get("loss")) spec.loss = enum_from(*loss, kFitLossNames);
  if (spec.free.empty() && spec.nuisance.empty())
    throw input_error(c.display, "free", "(missing)",
                      "nothing to fit: free at least one parameter of the law");
  return spec;
}

}  // namespace shpb
