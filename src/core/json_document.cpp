#include "core/json_document.hpp"

#include <set>
#include <vector>

#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/interrupt.hpp"
#include "core/json_value.hpp"

namespace shpb {
namespace {

using nlohmann::json;

// Line and column (1-based) of a byte offset, for parse errors.
std::string line_column(const std::string& text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// The JSON path of the value being parsed, kept up to date from nlohmann's parser callback. It
// names a duplicate key where it occurs, and a number that overflows a double (nlohmann reports
// no position for that).
class ParsePath {
 public:
  explicit ParsePath(std::string display) : display_(std::move(display)) {}

  void on_event(json::parse_event_t event, const json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        frames_.push_back({false, 0, false, "", {}});
        break;
      case json::parse_event_t::array_start:
        frames_.push_back({true, 0, false, "", {}});
        break;
      case json::parse_event_t::key: {
        auto& top = frames_.back();
        top.key = parsed.get<std::string>();
        top.has_key = true;
        if (!top.keys.insert(top.key).second)
          throw input_error(display_, path(), "", "duplicate key (each key may appear once)");
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        advance();
        break;
      case json::parse_event_t::value:
        advance();
        break;
    }
  }

  // Spelled as every other message spells a path (json_child_path: odd keys quoted).
  std::string path() const {
    std::string p;
    for (const auto& f : frames_) {
      if (f.array)
        p = json_element_path(p, f.index);
      else if (f.has_key)
        p = json_child_path(p, f.key);
    }
    return p;
  }

 private:
  struct Frame {
    bool array;
    std::size_t index;
    bool has_key;  // a key was read (the empty string is a key too)
    std::string key;
    std::set<std::string> keys;
  };

  void advance() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }

  std::string display_;
  std::vector<Frame> frames_;
};

// Builds the document as nlohmann's own DOM parser does (linear time: unlike its callback
// parser, which walks the parent object at every closing brace), while keeping the JSON path up
// to date and refusing nesting beyond kMaxJsonDepth before anything deep exists (nlohmann's
// dump, used in error messages, is recursive).
class Sax {
 public:
  Sax(json& root, std::string display)
      : dom_(root), where_(display), display_(std::move(display)) {}

  bool null() { return value(dom_.null()); }
  bool boolean(bool v) { return value(dom_.boolean(v)); }
  bool number_integer(json::number_integer_t v) { return value(dom_.number_integer(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return value(dom_.number_unsigned(v)); }
  bool number_float(json::number_float_t v, const json::string_t& s) {
    return value(dom_.number_float(v, s));
  }
  bool string(json::string_t& v) { return value(dom_.string(v)); }
  bool binary(json::binary_t& v) { return value(dom_.binary(v)); }
  bool start_object(std::size_t n) {
    enter();
    where_.on_event(json::parse_event_t::object_start, json());
    return dom_.start_object(n);
  }
  bool key(json::string_t& k) {
    where_.on_event(json::parse_event_t::key, json(k));
    return dom_.key(k);
  }
  bool end_object() {
    --depth_;
    where_.on_event(json::parse_event_t::object_end, json());
    return dom_.end_object();
  }
  bool start_array(std::size_t n) {
    enter();
    where_.on_event(json::parse_event_t::array_start, json());
    return dom_.start_array(n);
  }
  bool end_array() {
    --depth_;
    where_.on_event(json::parse_event_t::array_end, json());
    return dom_.end_array();
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& e) {
    return dom_.parse_error(position, token, e);  // throws it
  }
  std::string path() const { return where_.path(); }

 private:
  bool value(bool ok) {
    where_.on_event(json::parse_event_t::value, json());
    return ok;
  }
  void enter() {
    throw_if_interrupted();  // a huge document stops within a second of a signal
    if (++depth_ > kMaxJsonDepth) throw too_deep(display_, where_.path());
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  ParsePath where_;
  std::string display_;
  int depth_ = 0;
};

}  // namespace

InputError too_deep(const std::string& display, const std::string& path) {
  return input_error(display, path, "nesting deeper than " + std::to_string(kMaxJsonDepth),
                     "expected a scene-like document (objects and arrays a few levels deep)");
}

json parse_json_object(const std::string& text, const std::string& display) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw input_error(display, "", "empty file", "expected a JSON object");
  if (text.size() > kMaxJsonBytes)
    throw input_error(display, "", std::to_string(text.size()) + " bytes",
                      "expected at most " + std::to_string(kMaxJsonBytes) + " bytes of JSON");
  json j;
  Sax sax(j, display);
  try {
    json::sax_parse(text, &sax);
  } catch (const json::parse_error& e) {
    // e.what(): "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error
    // while parsing object - unexpected '}'; expected string literal"
    const std::string what = e.what();
    std::string place = line_column(text, e.byte == 0 ? 0 : e.byte - 1);
    std::string detail = what;
    if (const auto at = what.find("at line "); at != std::string::npos) {
      const auto colon = what.find(": ", at);
      if (colon != std::string::npos) {
        place = what.substr(at + 3, colon - at - 3);
        detail = what.substr(colon + 2);
      }
    }
    // The parser quotes what it read last, which may be bytes that are not text.
    for (auto& c : detail)
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x80) c = '?';
    throw input_error(display, place, detail, "expected valid JSON");
  } catch (const json::out_of_range& e) {  // "number overflow parsing '1e400'"
    std::string what = e.what();
    if (const auto end = what.find("] "); end != std::string::npos) what = what.substr(end + 2);
    throw input_error(display, sax.path(), what, "expected a number within the range of a double");
  }
  if (!j.is_object()) {
    std::string value = j.dump();
    if (value.size() > 40) value = value.substr(0, 37) + "...";
    throw input_error(display, "(top level)", value, "expected a JSON object { ... }");
  }
  return j;
}

std::string read_json_file_text(const std::filesystem::path& file, const std::string& display) {
  std::string bytes = read_input_file(file, display, "a JSON file", kMaxJsonBytes);
  // UTF-16 (Windows "Unicode" text) is named as such rather than as a syntax error at column 1.
  if (bytes.rfind("\xFF\xFE", 0) == 0 || bytes.rfind("\xFE\xFF", 0) == 0 ||
      bytes.find('\0') != std::string::npos)
    throw input_error(display, "line 1", "UTF-16 or binary data",
                      "expected JSON text in UTF-8; save the file as UTF-8");
  return bytes;
}

json read_json_object_file(const std::filesystem::path& file, const std::string& display) {
  return parse_json_object(read_json_file_text(file, display), display);
}

}  // namespace shpb
