#include "core/json_value.hpp"

#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/closest_match.hpp"
#include "core/csv_writer.hpp"
#include "core/number_format.hpp"

namespace shpb {

std::string json_child_path(const std::string& parent, std::string_view key) {
  bool plain = !key.empty();
  for (const char c : key)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) plain = false;
  if (plain) return parent.empty() ? std::string(key) : parent + "." + std::string(key);
  return parent + "[" + json_quoted(key) + "]";
}

std::string json_quoted(std::string_view s) {
  return nlohmann::json(std::string(s))
      .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string json_element_path(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

std::string JsonValue::text() const {
  constexpr std::size_t kMaxShown = 60;  // keep one-line messages readable
  std::string s = json_->dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (s.size() > kMaxShown) s = s.substr(0, kMaxShown - 3) + "...";
  return s;
}

InputError JsonValue::error(const std::string& constraint) const {
  return error_with_value(text(), constraint);
}

InputError JsonValue::error_with_value(const std::string& value,
                                       const std::string& constraint) const {
  return input_error(file_, path_.empty() ? "(top level)" : path_, value, constraint);
}

std::string JsonValue::format(double value_si, Dimension d) {
  const std::string unit(si_unit(d));
  return format_number(value_si) + (unit.empty() ? "" : " " + unit);
}

double JsonValue::quantity(Dimension d) const {
  if (json_->is_number()) {
    const double v = json_->get<double>();
    if (!std::isfinite(v)) throw error("expected a finite number");
    return v;
  }
  if (json_->is_string()) {
    try {
      return parse_quantity(json_->get<std::string>(), d);
    } catch (const std::invalid_argument& e) {
      throw error(e.what());
    }
  }
  throw error("expected " + std::string(to_string(d)) + ": a number or a string with a unit");
}

double JsonValue::positive_quantity(Dimension d) const {
  const double v = quantity(d);
  if (!(v > 0)) throw error_with_value(format(v, d), "must be > 0");
  return v;
}

double JsonValue::non_negative_quantity(Dimension d) const {
  const double v = quantity(d);
  if (!(v >= 0)) throw error_with_value(format(v, d), "must be >= 0");
  return v;
}

double JsonValue::quantity_in(Dimension d, double lo, double hi, bool lo_open, bool hi_open) const {
  const double v = quantity(d);
  const bool ok = (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  if (!ok)
    throw error_with_value(format(v, d), "must be in " + format_range(lo, hi, lo_open, hi_open));
  return v;
}

std::int64_t JsonValue::integer(std::int64_t lo, std::int64_t hi) const {
  std::string range("[");  // built piecewise: GCC 12 warns falsely on "[" + std::to_string()
  range.append(std::to_string(lo)).append(", ").append(std::to_string(hi)).append("]");
  if (!json_->is_number()) throw error("expected a whole number in " + range);
  const double v = json_->get<double>();
  if (!std::isfinite(v) || v != std::floor(v)) throw error("expected a whole number in " + range);
  if (v < static_cast<double>(lo) || v > static_cast<double>(hi))
    throw error("must be a whole number in " + range);
  return static_cast<std::int64_t>(v);
}

bool JsonValue::boolean() const {
  if (!json_->is_boolean()) throw error("expected true or false");
  return json_->get<bool>();
}

std::string JsonValue::string() const {
  if (!json_->is_string()) throw error("expected a string");
  return json_->get<std::string>();
}

std::string header_name_problem(std::string_view s) {
  if (s.empty() || s.find_first_not_of(' ') == std::string::npos) return "must not be empty";
  if (s.find_first_of("\r\n") != std::string::npos)
    return "must not contain a line break (a header's name is one line)";
  // Names are compared exactly as written: two that differ only in white space or in invisible
  // characters would be distinct here and the same to a reader that trims.
  if (std::isspace(static_cast<unsigned char>(s.front())) ||
      std::isspace(static_cast<unsigned char>(s.back())))
    return "must not begin or end with white space (names are compared exactly)";
  for (const unsigned char c : s)
    if (c < 0x20 || c == 0x7f) return "must not contain control characters (tab, NUL, escape...)";
  return "";
}

std::string name_problem(std::string_view s) {
  if (s.find_first_of(",\"\r\n") != std::string::npos)
    return "must not contain a comma, quote or line break (names become CSV column names)";
  return header_name_problem(s);
}

std::string file_name_problem(std::string_view s, const std::vector<std::string>& reserved) {
  if (std::string why = name_problem(s); !why.empty()) return why;
  if (s.find_first_of("/\\") != std::string_view::npos)
    return "must not contain a path separator (the name is a folder name)";
  if (s == "." || s == "..") return "must not be \".\" or \"..\" (the name is a folder name)";
  // NAME_MAX of Linux, macOS and Windows file systems: a longer folder cannot be created.
  constexpr std::size_t kMaxFolderNameBytes = 255;
  if (s.size() > kMaxFolderNameBytes)
    return "must be at most " + std::to_string(kMaxFolderNameBytes) + " bytes (" +
           std::to_string(s.size()) + " given; the name is a folder name)";
  const auto lower = [](std::string_view t) {
    std::string l(t);
    for (char& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return l;
  };
  for (const std::string& r : reserved)
    if (lower(s) == lower(r))
      return "is the name of one of the output's own files (" + r + "): choose another name";
  return "";
}

std::string JsonValue::name() const {
  const std::string s = string();
  if (const std::string why = name_problem(s); !why.empty()) throw error(why);
  return s;
}

std::string JsonValue::header_name() const {
  const std::string s = string();
  if (const std::string why = header_name_problem(s); !why.empty()) throw error(why);
  return s;
}

std::string JsonValue::file_name(const std::vector<std::string>& reserved) const {
  const std::string s = string();
  if (const std::string why = file_name_problem(s, reserved); !why.empty()) throw error(why);
  return s;
}

std::vector<JsonValue> JsonValue::array() const {
  if (!json_->is_array()) throw error("expected an array [ ... ]");
  std::vector<JsonValue> items;
  items.reserve(json_->size());
  for (std::size_t i = 0; i < json_->size(); ++i)
    items.emplace_back((*json_)[i], file_, json_element_path(path_, i));
  return items;
}

UnknownKeyError::UnknownKeyError(std::string file, std::string path, std::string key,
                                 std::vector<std::string> allowed)
    : InputError(input_error(file, path, "unknown key", key_suggestion_text(key, allowed, {}))),
      file_(std::move(file)),
      path_(std::move(path)),
      key_(std::move(key)),
      allowed_(std::move(allowed)) {}

InputError UnknownKeyError::placed(const std::vector<KeyPlace>& schema) const {
  return input_error(file_, path_, "unknown key", key_suggestion_text(key_, allowed_, schema));
}

JsonObject JsonValue::object(const std::vector<std::string>& allowed_keys) const {
  if (!json_->is_object()) throw error("expected an object { ... }");
  for (const auto& [key, value] : json_->items()) {
    bool known = false;
    for (const auto& k : allowed_keys) known = known || k == key;
    if (!known) throw UnknownKeyError(file_, json_child_path(path_, key), key, allowed_keys);
  }
  return JsonObject(*this);
}

std::optional<JsonValue> JsonObject::get(std::string_view key) const {
  const auto it = value_.json().find(key);
  if (it == value_.json().end()) return std::nullopt;
  return JsonValue(*it, value_.file(), json_child_path(value_.path(), key));
}

JsonValue JsonObject::require(std::string_view key, const std::string& what) const {
  if (auto v = get(key)) return *v;
  throw input_error(value_.file(), json_child_path(value_.path(), key), "(missing)",
                    "required: " + what);
}

}  // namespace shpb
