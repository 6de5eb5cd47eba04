#include "model/scene_writer.hpp"

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"
#include "core/json_document.hpp"
#include "core/output_folder.hpp"
#include "model/scene_inputs.hpp"

namespace shpb {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;  // the user's keys in the user's order

// A value in SI units as the reader reads it back bit for bit, its exponent without sign or
// leading zeros ("1.9e11 Pa", "1e-5 m"; std::to_chars writes "1.9e+11", "1e-05").
std::string si(double value, const char* unit) {
  std::string text = format_double(value);
  if (const auto e = text.find('e'); e != std::string::npos) {
    std::size_t digits = e + 1 + (text[e + 1] == '-' || text[e + 1] == '+');
    if (text[e + 1] == '+') text.erase(e + 1, 1), --digits;
    while (digits + 1 < text.size() && text[digits] == '0') text.erase(digits, 1);
  }
  return text + " " + unit;
}

// The text of a valid JSON document: the end of the value starting at `at` (its first
// character, no whitespace before it).
std::size_t value_end(const std::string& text, std::size_t at) {
  if (text[at] == '"') {
    std::size_t i = at + 1;
    while (text[i] != '"') i += text[i] == '\\' ? 2 : 1;
    return i + 1;
  }
  if (text[at] != '{' && text[at] != '[') {
    std::size_t i = at;
    while (i < text.size() &&
           std::string_view(",]} \t\r\n").find(text[i]) == std::string_view::npos)
      ++i;
    return i;
  }
  int depth = 0;
  for (std::size_t i = at;; ++i) {
    if (text[i] == '"')
      i = value_end(text, i) - 1;
    else if (text[i] == '{' || text[i] == '[')
      ++depth;
    else if ((text[i] == '}' || text[i] == ']') && --depth == 0)
      return i + 1;
  }
}

std::size_t skip_blank(const std::string& text, std::size_t i) {
  while (i < text.size() && std::string_view(" \t\r\n").find(text[i]) != std::string_view::npos)
    ++i;
  return i;
}

// `now` written where `text` holds `before` at [at, end): the user's own text (indents, number
// forms, spacing) kept for every value unchanged, down to the members of an object whose keys
// are the same and the elements of an array of the same length; a changed value, or an object
// with keys added or removed, written anew, indented as the line it starts on.
void keep_text(const std::string& text, std::size_t at, std::size_t end, const Json& before,
               const Json& now, std::string& out) {
  const bool same_keys =
      before.is_object() && now.is_object() && before.size() == now.size() &&
      std::equal(before.items().begin(), before.items().end(), now.items().begin(),
                 [](const auto& a, const auto& b) { return a.key() == b.key(); });
  const bool same_length = before.is_array() && now.is_array() && before.size() == now.size();
  if (before == now) {
    out.append(text, at, end - at);
  } else if (same_keys || same_length) {
    out += text[at];  // the bracket
    std::size_t i = at + 1;
    auto member = now.begin();
    for (const auto& old : before) {
      std::size_t v = skip_blank(text, i);
      if (text[v] == ',') v = skip_blank(text, v + 1);
      if (same_keys) v = skip_blank(text, skip_blank(text, value_end(text, v)) + 1);  // key, ':'
      const std::size_t e = value_end(text, v);
      out.append(text, i, v - i);
      keep_text(text, v, e, old, *member++, out);
      i = e;
    }
    out.append(text, i, end - i);
  } else {
    const std::size_t line = text.rfind('\n', at) + 1;  // npos + 1: the first line
    const std::string indent(skip_blank(text, line) - line, ' ');
    std::string written = now.dump(2);
    for (std::size_t n = written.find('\n'); n != std::string::npos; n = written.find('\n', n + 1))
      written.insert(n + 1, indent);
    out += written;
  }
}

// `key` of `o` set to `value` where the scene read holds `before` and the edited one `after`.
template <class T, class Value>
void patch(Json& o, const char* key, const T& before, const T& after, const Value& value) {
  if (!(before == after)) o[key] = value;
}

// `key` of `o` set to `text(after)` where an optional value was edited, removed where it is unset.
template <class T, class Text>
void patch_optional(Json& o, const char* key, const std::optional<T>& before,
                    const std::optional<T>& after, const Text& text) {
  if (before == after) return;
  if (after)
    o[key] = text(*after);
  else
    o.erase(key);
}

bool names_material(const Json& scene, const Json& v) {
  return v.is_string() && scene.contains("materials") && scene["materials"].is_object() &&
         scene["materials"].contains(v.get<std::string>());
}

// Every path the scene gives relative to its folder, from `from` to `to`: bar and plan shaper
// materials that are files, the measurement's files and the calibration.
void rebase_paths(Json& j, const fs::path& from, const fs::path& to) {
  const auto rebase = [&](Json& v) {
    if (v.is_string() && !names_material(j, v)) v = rebased_path(v.get<std::string>(), from, to);
  };
  if (j.contains("bars") && j["bars"].is_array())
    for (auto& b : j["bars"])
      if (b.is_object() && b.contains("material")) rebase(b["material"]);
  if (j.contains("calibration")) rebase(j["calibration"]);
  if (j.contains("measurement") && j["measurement"].is_object()) {
    auto& m = j["measurement"];
    if (m.contains("file")) rebase(m["file"]);
    if (m.contains("channels") && m["channels"].is_array())
      for (auto& c : m["channels"])
        if (c.is_object() && c.contains("file")) rebase(c["file"]);
  }
  if (j.contains("plan") && j["plan"].is_object() && j["plan"].contains("shaper") &&
      j["plan"]["shaper"].is_object() && j["plan"]["shaper"].contains("material")) {
    auto& m = j["plan"]["shaper"]["material"];
    if (m.is_array())
      for (auto& s : m) rebase(s);
    else
      rebase(m);
  }
}

void patch_johnson_cook(Json& o, const JohnsonCookParams& a, const JohnsonCookParams& b) {
  patch(o, "A", a.A_Pa, b.A_Pa, si(b.A_Pa, "Pa"));
  patch(o, "B", a.B_Pa, b.B_Pa, si(b.B_Pa, "Pa"));
  patch(o, "n", a.n, b.n, b.n);
  patch(o, "C", a.C, b.C, b.C);
  patch(o, "m", a.m, b.m, b.m);
  patch(o, "reference_strain_rate", a.reference_strain_rate_1_s, b.reference_strain_rate_1_s,
        si(b.reference_strain_rate_1_s, "1/s"));
  patch(o, "room_temperature", a.room_temperature_K, b.room_temperature_K,
        si(b.room_temperature_K, "K"));
  patch(o, "melting_temperature", a.melting_temperature_K, b.melting_temperature_K,
        si(b.melting_temperature_K, "K"));
  // The test's own temperature, or none: the test follows the room temperature.
  if (b.temperature_given)
    patch(o, "temperature", a.initial_temperature_K, b.initial_temperature_K,
          si(b.initial_temperature_K, "K"));
  else
    o.erase("temperature");
  if (b.specific_heat_given)
    patch(o, "specific_heat", a.specific_heat_J_kgK, b.specific_heat_J_kgK,
          si(b.specific_heat_J_kgK, "J/(kg K)"));
  patch(o, "taylor_quinney", a.taylor_quinney, b.taylor_quinney, b.taylor_quinney);
  patch(o, "adiabatic", a.adiabatic, b.adiabatic, b.adiabatic);
  patch_optional(o, "strain_rate_filter", a.strain_rate_filter_s, b.strain_rate_filter_s,
                 [](double v) { return si(v, "s"); });
}

// The material object `o` (as the scene or its file gives it, read as `a`) edited to `b`.
void patch_material(Json& o, const MaterialSpec& a, const MaterialSpec& b) {
  patch(o, "density", a.density_kg_m3, b.density_kg_m3, si(b.density_kg_m3, "kg/m3"));
  patch(o, "poisson_ratio", a.poisson_ratio, b.poisson_ratio, b.poisson_ratio);
  if (b.model == MaterialModel::kViscoelastic) {
    patch(o, "long_term_modulus", a.viscoelastic.long_term_modulus_Pa,
          b.viscoelastic.long_term_modulus_Pa, si(b.viscoelastic.long_term_modulus_Pa, "Pa"));
    for (std::size_t k = 0; k < b.viscoelastic.arms.size() && o.contains("arms"); ++k) {
      const MaxwellArm &x = a.viscoelastic.arms.at(k), &y = b.viscoelastic.arms[k];
      patch(o["arms"][k], "modulus", x.modulus_Pa, y.modulus_Pa, si(y.modulus_Pa, "Pa"));
      patch(o["arms"][k], "relaxation_time", x.relaxation_time_s, y.relaxation_time_s,
            si(y.relaxation_time_s, "s"));
    }
    return;  // its modulus is derived
  }
  patch(o, "youngs_modulus", a.youngs_modulus_Pa, b.youngs_modulus_Pa,
        si(b.youngs_modulus_Pa, "Pa"));
  if (b.model == MaterialModel::kBilinear) {
    patch(o, "yield_stress", a.bilinear.yield_stress_Pa, b.bilinear.yield_stress_Pa,
          si(b.bilinear.yield_stress_Pa, "Pa"));
    patch(o, "tangent_modulus", a.bilinear.tangent_modulus_Pa, b.bilinear.tangent_modulus_Pa,
          si(b.bilinear.tangent_modulus_Pa, "Pa"));
  }
  if (b.model == MaterialModel::kJohnsonCook) patch_johnson_cook(o, a.johnson_cook, b.johnson_cook);
}

// The bars' edited materials: a named one every bar of that name edited alike in `materials`, any
// other inline in its bar (the material object its bar, `materials` or its file gave, edited).
void patch_materials(Json& j, const Scene& read, const Scene& edited) {
  std::map<std::string, std::vector<std::size_t>> by_name;  // edited bars of each named material
  std::map<std::string, bool> alike;
  for (std::size_t i = 0; i < edited.bars.size(); ++i) {
    const Json& m = j["bars"][i].contains("material") ? j["bars"][i]["material"] : Json();
    if (!names_material(j, m)) continue;
    const std::string key = m.get<std::string>();
    auto [it, first] = alike.try_emplace(key, true);
    if (!by_name[key].empty())
      it->second = it->second && edited.bars[i].material == edited.bars[by_name[key][0]].material;
    by_name[key].push_back(i);
  }
  for (const auto& [key, bars] : by_name)
    if (alike[key] && !(read.bars[bars[0]].material == edited.bars[bars[0]].material))
      patch_material(j["materials"][key], read.bars[bars[0]].material,
                     edited.bars[bars[0]].material);
  for (std::size_t i = 0; i < edited.bars.size(); ++i) {
    const MaterialSpec &a = read.bars[i].material, &b = edited.bars[i].material;
    if (a == b) continue;  // a bar without a material among them
    Json& m = j["bars"][i]["material"];
    if (names_material(j, m) && alike[m.get<std::string>()]) continue;
    Json inline_material = m.is_object() ? m
                           : names_material(j, m)
                               ? j["materials"][m.get<std::string>()]
                               : Json::parse(read_json_file_text(a.name, a.name));
    patch_material(inline_material, a, b);
    m = inline_material;
  }
}

void patch_bars(Json& j, const Scene& read, const Scene& edited) {
  for (std::size_t i = 0; i < edited.bars.size(); ++i) {
    const BarSpec &a = read.bars[i], &b = edited.bars[i];
    Json& o = j["bars"][i];
    patch(o, "length", a.length_m, b.length_m, si(b.length_m, "m"));
    if (b.area_given)
      patch(o, "area", a.area_m2, b.area_m2, si(b.area_m2, "m2"));
    else
      patch(o, "diameter", a.diameter_m, b.diameter_m, si(b.diameter_m, "m"));
    patch(o, "velocity", a.velocity_m_s, b.velocity_m_s, si(b.velocity_m_s, "m/s"));
    if (b.elements > 0)
      patch(o, "elements", a.elements, b.elements, b.elements);
    else
      o.erase("elements");
    if (b.gap_m > 0 || o.contains("gap")) patch(o, "gap", a.gap_m, b.gap_m, si(b.gap_m, "m"));
    patch(o, "inertia", a.inertia, b.inertia, b.inertia);
  }
  patch_materials(j, read, edited);
}

void patch_run(Json& j, const Scene& read, const Scene& edited) {
  patch(j, "name", read.name, edited.name, edited.name);
  const SimulationSpec &a = read.simulation, &b = edited.simulation;
  Json& s = j["simulation"];
  const auto number = [](double v) { return v; };
  patch_optional(s, "duration", a.duration_s, b.duration_s, [](double v) { return si(v, "s"); });
  patch_optional(s, "tolerance", a.tolerance, b.tolerance, number);
  patch(s, "stepping", a.stepping, b.stepping, std::string(to_string(b.stepping)));
  patch_optional(s, "courant", a.courant, b.courant, number);
  if (s.empty()) j.erase("simulation");
  if (read.contact.method != edited.contact.method)
    j["contact"]["method"] = std::string(to_string(edited.contact.method));
}

// `s` as compared with the scene read back from its written text: what names its source (file,
// text, material files read, the paths as written) and what a run sets (the mesh choice's time and
// note) taken from `back`, each path absolute.
Scene compared(Scene s, const Scene& back) {
  s.file = back.file;
  s.source_text = back.source_text;
  s.material_files = back.material_files;
  std::error_code ec;
  for (std::size_t i = 0; i < s.bars.size() && i < back.bars.size(); ++i) {
    std::string& name = s.bars[i].material.name;
    const std::string& now = back.bars[i].material.name;  // inline, or its file from elsewhere
    if (name != now && (now == "inline" || fs::equivalent(name, now, ec))) name = now;
  }
  if (s.plan && back.plan && s.plan->shaper_materials.size() == back.plan->shaper_materials.size())
    for (std::size_t k = 0; k < s.plan->shaper_materials.size(); ++k)
      s.plan->shaper_materials[k].text = back.plan->shaper_materials[k].text;
  s.simulation.mesh_choice_time_s = back.simulation.mesh_choice_time_s;
  s.simulation.tolerance_withheld = back.simulation.tolerance_withheld;
  s.simulation.tolerance_is_default = back.simulation.tolerance_is_default;
  const auto whole = [](fs::path& p) {
    if (!p.empty()) p = fs::absolute(p).lexically_normal();
  };
  whole(s.calibration_file);
  if (s.measurement) {
    whole(s.measurement->file);
    for (auto& c : s.measurement->channels) whole(c.file);
  }
  return s;
}

// The first part of the scenes that differs, for the refusal.
std::string first_difference(const Scene& a, const Scene& b) {
  if (a.name != b.name) return "name";
  for (std::size_t i = 0; i < a.bars.size() && i < b.bars.size(); ++i) {
    const std::string bar = "bars[" + std::to_string(i) + "]";
    if (!(a.bars[i].material == b.bars[i].material)) return bar + ".material";
    if (!(a.bars[i] == b.bars[i])) return bar;
  }
  if (!(a.simulation == b.simulation)) return "simulation";
  if (!(a.contact == b.contact)) return "contact";
  if (!(a.measurement == b.measurement)) return "measurement";
  if (!(a.plan == b.plan)) return "plan";
  return "calibration";
}

}  // namespace

std::string rebased_path(const std::string& written, const fs::path& from_dir,
                         const fs::path& to_dir) {
  // Lexically, as the reader resolves it ((folder / path).lexically_normal()): a symlinked folder
  // on the way stays as the scene names it.
  const fs::path target = fs::absolute(from_dir / written).lexically_normal();
  return target.lexically_relative(fs::absolute(to_dir).lexically_normal()).string();
}

std::string scene_file_text(const Scene& scene, const fs::path& file) {
  const std::string shown = file.string();
  if (scene.source_text.empty())
    throw input_error(shown, "", "a scene not read from a scene file",
                      "expected a scene read by Scene.load or Scene.from_dict");
  const fs::path to = fs::absolute(file);
  Json j = Json::parse(scene.source_text);
  rebase_paths(j, fs::absolute(scene.file).parent_path(), to.parent_path());
  // The file's own values as read from the new place (a name taken from the file's name changes
  // with it), then every value that differs from the edited scene.
  const Scene read = read_scene_text(j.dump(), to);
  patch_run(j, read, scene);
  patch_bars(j, read, scene);
  std::string text;
  const std::size_t start =
      skip_blank(scene.source_text, scene.source_text.starts_with("\xEF\xBB\xBF") ? 3 : 0);
  keep_text(scene.source_text, start, value_end(scene.source_text, start),
            Json::parse(scene.source_text), j, text);
  text += "\n";
  const Scene back = read_scene_text(text, to);
  if (const Scene mine = compared(scene, back), theirs = compared(back, back); !(mine == theirs))
    throw input_error(shown, first_difference(mine, theirs), "as edited",
                      "cannot be written: the file would read back as another scene (a value "
                      "the scene's calibration replaces whenever it is read, or one no scene "
                      "file gives)");
  return text;
}

void save_scene(const Scene& scene, const fs::path& file, bool overwrite) {
  const fs::path to = fs::absolute(file).lexically_normal();
  std::error_code ec;
  if (fs::exists(to, ec) && !fs::is_directory(to, ec)) {
    if (!overwrite)
      throw input_error(file.string(), "", "", "exists: give overwrite=True to replace it");
    for (const fs::path& input : scene_inputs(scene))
      if (input != scene.file && fs::equivalent(input, to, ec))
        throw input_error(file.string(), "", "", "is a file the scene reads: not replaced");
    try {
      read_scene(to);
    } catch (const InputError& e) {  // a record, a table, a material or calibration file, ...
      throw input_error(
          file.string(), "", "",
          "is not a scene file (reading it as one: " + std::string(e.what()) + "): not replaced");
    }
  }
  // Its folder is made first: the text is read back from there (removed on failure).
  OutputFile out(to);
  write_text_file(out.path(), scene_file_text(scene, to));
  out.commit();
}

}  // namespace shpb
