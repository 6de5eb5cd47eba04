#include "model/plan_reader.hpp"

#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"
#include "model/input_keys.hpp"

namespace shpb {
namespace {

namespace fs = std::filesystem;

// A quantity, or [lo, hi] with 0 < lo ≤ hi.
PlanRange read_range(const JsonValue& v, Dimension d) {
  if (!v.json().is_array()) {
    const double x = v.positive_quantity(d);
    return {x, x};
  }
  const auto items = v.array();
  if (items.size() != 2) throw v.error("expected a quantity or a range [lo, hi] of two quantities");
  PlanRange r{items[0].positive_quantity(d), items[1].positive_quantity(d)};
  if (r.hi < r.lo) throw v.error("expected a range [lo, hi] with lo ≤ hi");
  return r;
}

// The shaper bar of each allowed material, read by the scene reader from the scene with the
// shaper inserted between the striker and the incident bar.
std::vector<ShaperMaterial> read_shaper_materials(const JsonValue& v, const nlohmann::json& scene,
                                                  const fs::path& file) {
  std::vector<JsonValue> items;
  if (v.json().is_array())
    items = v.array();
  else
    items.push_back(v);
  if (items.empty()) throw v.error("expected a material name or path, or a list of them");
  std::vector<ShaperMaterial> out;
  for (const auto& item : items) {
    const std::string s = item.string();
    // Each material once: a second search of the same shapers is no other choice.
    for (const ShaperMaterial& m : out)
      if (m.text == s) throw item.error("listed twice: each shaper material once");
    const bool named = scene.contains("materials") && scene["materials"].is_object() &&
                       scene["materials"].contains(s);
    std::error_code ec;
    if (!named && !fs::is_regular_file((file.parent_path() / s).lexically_normal(), ec))
      throw item.error(
          "neither a name from the scene's materials nor a material file (paths are "
          "relative to the scene)");
    nlohmann::json j = scene;
    j.erase("plan");
    j.erase("measurement");
    j["bars"].insert(
        j["bars"].begin() + 1,
        nlohmann::json{{"name", "shaper"}, {"material", s}, {"length", 1e-3}, {"diameter", 1e-2}});
    out.push_back({s, read_scene_text(j.dump(), file).bars[1]});
  }
  return out;
}

}  // namespace

PlanSpec read_plan_block(const JsonValue& plan, const Scene& scene,
                         const nlohmann::json& scene_json, const fs::path& file) {
  const auto o = plan.object(input_keys::kPlan);
  const auto incident = scene.incident_bar();
  if (!scene.specimen || !incident || !scene.transmitter_bar() || scene.bars[0].velocity_m_s == 0)
    throw plan.error(
        "planning needs a striker (the first bar, with a velocity), an incident bar with a gauge, "
        "the specimen and a transmitter bar with a gauge");
  // The search plans compression tests: a striker driving the bars, the specimen's rate positive
  // (docs/methods.md §12). A striker pulled away (a tension bar's) was planned as a compression
  // test with its velocity's sign turned.
  if (scene.bars[0].velocity_m_s < 0)
    throw input_error(plan.file(), "bars[0].velocity",
                      format_double(scene.bars[0].velocity_m_s) + " m/s",
                      "plan searches compression tests (a striker moving toward the bars, "
                      "velocity > 0); a tension test is not planned");
  PlanSpec spec;
  spec.scene_has_shaper = *incident == 2;
  if (*incident > 2)
    throw plan.error(
        "planning expects at most one bar (a pulse shaper) between "
        "the striker and the incident bar");
  if (auto v = o.get("notes")) v->string();
  const auto striker = JsonObject(o.require("striker",
                                            "the striker's bounds, e.g. {\"velocity\": [\"5 m/s\", "
                                            "\"40 m/s\"]}"))
                           .value()
                           .object(input_keys::kPlanStriker);
  const double length = scene.bars[0].length_m;
  spec.striker_length = {length, length};
  if (auto v = striker.get("length")) spec.striker_length = read_range(*v, Dimension::kLength);
  spec.striker_velocity =
      read_range(striker.require("velocity", "e.g. [\"5 m/s\", \"40 m/s\"]"), Dimension::kVelocity);
  if (auto v = o.get("specimen"))
    spec.specimen_length = read_range(
        v->object(input_keys::kPlanSpecimen).require("length", "e.g. [\"3 mm\", \"8 mm\"]"),
        Dimension::kLength);
  if (auto v = o.get("shaper")) {
    const auto s = v->object(input_keys::kPlanShaper);
    const BarSpec* own = spec.scene_has_shaper ? &scene.bars[1] : nullptr;
    if (own && !s.has("material"))
      spec.shaper_materials.push_back({"", *own});
    else
      spec.shaper_materials = read_shaper_materials(
          s.require("material",
                    "the shaper's material (a name from materials or a file), or a "
                    "list of them"),
          scene_json, file);
    auto range = [&](const char* key, double given) {
      if (own && !s.has(key)) return PlanRange{given, given};
      return read_range(s.require(key, "e.g. [\"0.5 mm\", \"3 mm\"]"), Dimension::kLength);
    };
    spec.shaper_diameter = range("diameter", own ? own->diameter_m : 0);
    spec.shaper_thickness = range("thickness", own ? own->length_m : 0);
  }
  return spec;
}

}  // namespace shpb
