#pragma once
// An enum's names both ways, from one table of {value, name} pairs, so that each name is spelled
// once: the settings that take a name (simulation.implicit_solver, --gl) and the golden
// results' outcomes read their tables through nameOf and valueNamed.

#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>

namespace particles {

template <typename Enum>
using NameTableRow = std::pair<Enum, std::string_view>;

// The name of `value`, or `unknown` when the table lacks it.
template <typename Enum, std::size_t N>
constexpr std::string_view nameOf(const NameTableRow<Enum> (&table)[N], Enum value, std::string_view unknown) {
  for (const auto& [v, name] : table) {
    if (v == value) return name;
  }
  return unknown;
}

// The value named `name` exactly, if any.
template <typename Enum, std::size_t N>
constexpr std::optional<Enum> valueNamed(const NameTableRow<Enum> (&table)[N], std::string_view name) {
  for (const auto& [v, n] : table) {
    if (n == name) return v;
  }
  return std::nullopt;
}

}  // namespace particles
