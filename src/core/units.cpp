#include "core/units.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/json_value.hpp"

// A unit expression is a product of powers of symbols with optional SI prefixes, e.g. "g/cm3",
// "J/(kg K)", "m·s^-1", "1/s". Each symbol carries a factor to SI and a dimension vector over the
// base quantities (length, mass, time, temperature, current); a quantity is accepted when its
// dimension vector equals the expected one. "°C"/"degC" (an offset scale) is only valid alone.

namespace shpb {
namespace {

constexpr int kBases = 5;  // L, M, T, Θ, I
using Exponents = std::array<int, kBases>;

struct DimensionInfo {
  Dimension dimension;
  Exponents exponents;
  std::string_view name;     // "a length"
  std::string_view si;       // "m"
  std::string_view example;  // "20 mm"
};

constexpr std::array<DimensionInfo, 16> kDimensions = {{
    {Dimension::kDimensionless, {0, 0, 0, 0, 0}, "a plain number", "", "0.3"},
    {Dimension::kLength, {1, 0, 0, 0, 0}, "a length", "m", "20 mm"},
    {Dimension::kArea, {2, 0, 0, 0, 0}, "an area", "m^2", "285 mm2"},
    {Dimension::kTime, {0, 0, 1, 0, 0}, "a time", "s", "600 us"},
    {Dimension::kFrequency, {0, 0, -1, 0, 0}, "a frequency", "Hz", "10 MHz"},
    {Dimension::kMass, {0, 1, 0, 0, 0}, "a mass", "kg", "1.2 kg"},
    {Dimension::kDensity, {-3, 1, 0, 0, 0}, "a density", "kg/m^3", "7.85 g/cm3"},
    {Dimension::kPressure, {-1, 1, -2, 0, 0}, "a stress", "Pa", "200 GPa"},
    {Dimension::kVelocity, {1, 0, -1, 0, 0}, "a velocity", "m/s", "15 m/s"},
    {Dimension::kForce, {1, 1, -2, 0, 0}, "a force", "N", "10 kN"},
    {Dimension::kEnergy, {2, 1, -2, 0, 0}, "an energy", "J", "5 J"},
    {Dimension::kVoltage, {2, 1, -3, 0, -1}, "a voltage", "V", "10 V"},
    {Dimension::kTemperature, {0, 0, 0, 1, 0}, "a temperature", "K", "20 degC"},
    {Dimension::kSpecificHeat, {2, 0, -2, -1, 0}, "a specific heat", "J/(kg K)", "900 J/(kg K)"},
    {Dimension::kStrainRate, {0, 0, -1, 0, 0}, "a strain rate", "1/s", "1000 1/s"},
    {Dimension::kStiffness, {0, 1, -2, 0, 0}, "a stiffness", "N/m", "1e9 N/m"},
}};

const DimensionInfo& info(Dimension d) {
  for (const auto& i : kDimensions)
    if (i.dimension == d) return i;
  return kDimensions[0];
}

struct Symbol {
  std::string_view text;
  double factor;  // SI value of one unit
  Exponents exponents;
  bool prefixable;
};

constexpr std::array<Symbol, 14> kSymbols = {{
    {"m", 1.0, {1, 0, 0, 0, 0}, true},
    {"g", 1e-3, {0, 1, 0, 0, 0}, true},
    {"s", 1.0, {0, 0, 1, 0, 0}, true},
    {"Hz", 1.0, {0, 0, -1, 0, 0}, true},
    {"Pa", 1.0, {-1, 1, -2, 0, 0}, true},
    {"N", 1.0, {1, 1, -2, 0, 0}, true},
    {"J", 1.0, {2, 1, -2, 0, 0}, true},
    {"V", 1.0, {2, 1, -3, 0, -1}, true},
    {"K", 1.0, {0, 0, 0, 1, 0}, false},
    {"bar", 1e5, {-1, 1, -2, 0, 0}, true},
    {"psi", 6894.757293168361, {-1, 1, -2, 0, 0}, false},  // lbf/in²
    {"ksi", 6894757.293168361, {-1, 1, -2, 0, 0}, false},
    {"in", 0.0254, {1, 0, 0, 0, 0}, false},
    {"1", 1.0, {0, 0, 0, 0, 0}, false},  // "1/s"
}};

struct Prefix {
  std::string_view text;
  double factor;
};
constexpr std::array<Prefix, 12> kPrefixes = {{{"p", 1e-12},
                                               {"n", 1e-9},
                                               {"u", 1e-6},
                                               {"\xC2\xB5", 1e-6},  // µ MICRO SIGN
                                               {"\xCE\xBC", 1e-6},  // μ GREEK SMALL LETTER MU
                                               {"m", 1e-3},
                                               {"c", 1e-2},
                                               {"d", 1e-1},
                                               {"k", 1e3},
                                               {"M", 1e6},
                                               {"G", 1e9},
                                               {"T", 1e12}}};

constexpr std::string_view kCelsius[] = {"degC",
                                         "\xC2\xB0"
                                         "C",
                                         "celsius"};
constexpr double kCelsiusOffsetK = 273.15;

struct UnitValue {
  double factor = 1.0;
  Exponents exponents{};
};

std::string describe_exponents(const Exponents& e) {
  for (const auto& i : kDimensions)
    if (i.exponents == e) return std::string(i.name);
  static constexpr std::string_view kBaseSymbols[kBases] = {"m", "kg", "s", "K", "A"};
  std::string s;
  for (int b = 0; b < kBases; ++b) {
    if (e[b] == 0) continue;
    if (!s.empty()) s += ' ';
    s += kBaseSymbols[b];
    if (e[b] != 1) s += '^' + std::to_string(e[b]);
  }
  return "a quantity in " + s;
}

// Recursive-descent parser over the unit text. A '/' divides by everything up to the next '/'
// or ')', so "J/kg K" reads as J/(kg K).
class UnitParser {
 public:
  explicit UnitParser(std::string_view text) : text_(text) {}

  UnitValue parse() {
    UnitValue u = expression();
    skip_spaces();
    if (pos_ != text_.size()) fail("unexpected " + json_quoted(text_.substr(pos_)));
    return u;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw std::invalid_argument(what); }

  void skip_spaces() {
    while (pos_ < text_.size() && text_[pos_] == ' ') ++pos_;
  }

  bool at_multiply() {
    if (text_.substr(pos_, 2) == "\xC2\xB7") {  // · MIDDLE DOT
      pos_ += 2;
      return true;
    }
    if (pos_ < text_.size() && text_[pos_] == '*') {
      ++pos_;
      return true;
    }
    return false;
  }

  bool at_factor_start() const {
    if (pos_ >= text_.size()) return false;
    const char c = text_[pos_];
    return c == '(' || c == '1' || is_symbol_byte(c);
  }

  static bool is_symbol_byte(char c) {
    const auto u = static_cast<unsigned char>(c);
    return (u >= 'a' && u <= 'z') || (u >= 'A' && u <= 'Z') || u >= 0x80;
  }

  // expression := [product] { '/' product }
  UnitValue expression() {
    skip_spaces();
    // "/s" reads as "1/s".
    UnitValue u = pos_ < text_.size() && text_[pos_] == '/' ? UnitValue{} : product();
    skip_spaces();
    while (pos_ < text_.size() && text_[pos_] == '/') {
      ++pos_;
      const UnitValue d = product();
      u.factor /= d.factor;
      for (int b = 0; b < kBases; ++b) u.exponents[b] -= d.exponents[b];
      skip_spaces();
    }
    return u;
  }

  // product := factor { ('*' | '·' | ' ') factor }
  UnitValue product() {
    skip_spaces();
    UnitValue u = factor();
    while (true) {
      const std::size_t save = pos_;
      skip_spaces();
      const bool explicit_op = at_multiply();
      skip_spaces();
      if (!at_factor_start()) {
        if (explicit_op) fail("a unit is missing after the multiplication sign");
        pos_ = save;
        return u;
      }
      const UnitValue f = factor();
      u.factor *= f.factor;
      for (int b = 0; b < kBases; ++b) u.exponents[b] += f.exponents[b];
    }
  }

  // factor := ( '(' expression ')' | symbol ) [exponent]
  UnitValue factor() {
    UnitValue u;
    if (pos_ < text_.size() && text_[pos_] == '(') {
      ++pos_;
      u = expression();
      skip_spaces();
      if (pos_ >= text_.size() || text_[pos_] != ')') fail("a closing parenthesis is missing");
      ++pos_;
    } else if (pos_ < text_.size() && text_[pos_] == '1') {
      // Only the numerator of a quotient ("1/s"): a "1" with digits or a unit after it is a
      // second number ("5 12 mm" would read as 5 mm, its "12" as 1 to the power 2).
      ++pos_;
      skip_spaces();
      if (pos_ >= text_.size() || text_[pos_] != '/')
        fail(
            "\"1\" is a unit only as the numerator of a quotient, as in \"1/s\": a second "
            "number?");
      return u;
    } else {
      const std::size_t start = pos_;
      while (pos_ < text_.size() && is_symbol_byte(text_[pos_]) && !at_superscript() &&
             text_.substr(pos_, 2) != "\xC2\xB7")
        ++pos_;
      if (start == pos_) fail("a unit is missing");
      u = symbol(text_.substr(start, pos_ - start));
    }
    const int e = exponent();
    u.factor = std::pow(u.factor, e);
    for (auto& x : u.exponents) x *= e;
    return u;
  }

  bool at_superscript() const {
    const auto s = text_.substr(pos_, 2);
    return s == "\xC2\xB2" || s == "\xC2\xB3";
  }

  // exponent := '^' ['-'] digits | ['-'] digits | '²' | '³'
  int exponent() {
    if (text_.substr(pos_, 2) == "\xC2\xB2") return pos_ += 2, 2;
    if (text_.substr(pos_, 2) == "\xC2\xB3") return pos_ += 2, 3;
    const bool caret = pos_ < text_.size() && text_[pos_] == '^';
    std::size_t p = pos_ + (caret ? 1 : 0);
    const bool negative = p < text_.size() && text_[p] == '-';
    if (negative) ++p;
    if (p >= text_.size() || text_[p] < '0' || text_[p] > '9') {
      if (caret) fail("an integer exponent must follow '^'");
      return 1;
    }
    int e = 0;
    while (p < text_.size() && text_[p] >= '0' && text_[p] <= '9' && e < 100)
      e = 10 * e + (text_[p++] - '0');
    if (e == 0 || e >= 100) fail("exponents must be non-zero integers below 100");
    pos_ = p;
    return negative ? -e : e;
  }

  static UnitValue symbol(std::string_view s) {
    for (const auto& sym : kSymbols)
      if (sym.text == s) return {sym.factor, sym.exponents};
    for (const auto& p : kPrefixes) {
      if (s.size() <= p.text.size() || s.substr(0, p.text.size()) != p.text) continue;
      const auto rest = s.substr(p.text.size());
      for (const auto& sym : kSymbols)
        if (sym.prefixable && sym.text == rest) return {p.factor * sym.factor, sym.exponents};
    }
    for (const auto c : kCelsius)
      if (s == c)
        throw std::invalid_argument(
            "\xC2\xB0"
            "C is only valid on its own, as a temperature");
    throw std::invalid_argument("unknown unit \"" + std::string(s) + "\"");
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string_view to_string(Dimension d) { return info(d).name; }
std::string_view si_unit(Dimension d) { return info(d).si; }

std::string quantity_text(Dimension d) {
  const auto& i = info(d);
  return std::string(i.name) + " such as \"" + std::string(i.example) + "\"" +
         (i.si.empty() ? "" : " (a bare number is taken in " + std::string(i.si) + ")");
}

namespace {
std::string expected_text(Dimension d) { return "expected " + quantity_text(d); }
}  // namespace

double parse_quantity(std::string_view text, Dimension expected) {
  std::string_view t = trim(text);
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);  // from_chars takes no '+'
  double number = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), number);
  if (ec == std::errc::result_out_of_range)
    throw std::invalid_argument("the number is out of range; " + expected_text(expected));
  if (ec != std::errc() || !std::isfinite(number))
    throw std::invalid_argument("no number found; " + expected_text(expected));
  const std::string_view unit = trim(t.substr(static_cast<std::size_t>(end - t.data())));
  if (unit.empty()) return number;  // SI
  if (unit.size() > 1 && unit[0] == ',' && unit[1] >= '0' && unit[1] <= '9')
    throw std::invalid_argument("use a decimal point, not a comma; " + expected_text(expected));

  if (unit == "%") {  // percent: a plain number given in hundredths ("1 %" is 0.01)
    if (expected != Dimension::kDimensionless)
      throw std::invalid_argument("\"%\" is a plain number; " + expected_text(expected));
    return number / 100;
  }
  for (const auto c : kCelsius) {
    if (unit != c) continue;
    if (expected != Dimension::kTemperature)
      throw std::invalid_argument("\"" + std::string(unit) + "\" is a temperature; " +
                                  expected_text(expected));
    return number + kCelsiusOffsetK;
  }

  UnitValue u;
  try {
    u = UnitParser(unit).parse();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(e.what()) + "; " + expected_text(expected));
  }
  if (u.exponents != info(expected).exponents)
    throw std::invalid_argument("\"" + std::string(unit) + "\" is " +
                                describe_exponents(u.exponents) + "; " + expected_text(expected));
  const double value = number * u.factor;
  if (!std::isfinite(value))
    throw std::invalid_argument("the value is out of range; " + expected_text(expected));
  return value;
}

}  // namespace shpb
