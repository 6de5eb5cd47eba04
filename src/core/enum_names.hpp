#pragma once
// An enum's names as one table of {name, value} pairs beside the enum: the only place a spelling
// lives (scene files, the command line, outputs). Both directions and the list of names an error
// message offers are read from it.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace shpb {

template <typename Enum>
using EnumName = std::pair<std::string_view, Enum>;

template <typename Enum, std::size_t N>
constexpr std::string_view enum_name(const EnumName<Enum> (&table)[N], Enum value) {
  for (const auto& [name, v] : table)
    if (v == value) return name;
  return "?";
}

// std::nullopt for a name not in the table (callers report it with its place and enum_names).
template <typename Enum, std::size_t N>
constexpr std::optional<Enum> enum_value(const EnumName<Enum> (&table)[N], std::string_view name) {
  for (const auto& [n, v] : table)
    if (n == name) return v;
  return std::nullopt;
}

template <typename Enum, std::size_t N>
std::vector<std::string> enum_names(const EnumName<Enum> (&table)[N]) {
  std::vector<std::string> names;
  for (const auto& [n, v] : table) names.emplace_back(n);
  return names;
}

// The names for a message: "\"a\", \"b\" or \"c\"".
template <typename Enum, std::size_t N>
std::string enum_names_text(const EnumName<Enum> (&table)[N]) {
  std::string text;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) text += i + 1 == N ? " or " : ", ";
    text.append("\"").append(table[i].first).append("\"");
  }
  return text;
}

}  // namespace shpb
