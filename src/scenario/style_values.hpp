#pragma once
// The values a style section writes (docs/scenarios.md, "Style"): names from closed sets
// (quantities, colormaps, colour-bar settings), colours, lengths on the frame, colormap ranges and
// labels, each read from one Value and checked there. Internal to the scenario loader.

#include <fmt/format.h>

#include <string>
#include <string_view>
#include <vector>

#include "scenario/yaml_reader.hpp"
#include "style/style.hpp"

namespace particles::scenario::detail {

// Fails at `at`: "unknown WHAT 'NAME'; did you mean 'X'? (one of A, B, …)".
[[noreturn]] void failUnknownName(const Value& at, std::string_view what, const std::string& name,
                                  const std::vector<std::string>& known);

// The value of a closed set that `v` names through the set's fromName (style/style.hpp), or an
// error with the closest of `known`.
template <class FromName>
auto named(const Value& v, std::string_view what, FromName fromName, const std::vector<std::string>& known) {
  const std::string name = v.string();
  const auto value = fromName(name);
  if (!value) failUnknownName(v, what, name, known);
  return *value;
}

// Whether `v` is a plain (unquoted) number, or true or false, as Value::number and Value::boolean
// read them: for keys that take such a value or a word.
bool isNumber(const Value& v);
bool isBoolean(const Value& v);

// `viridis`, `magma_r`, …: style::colormapNames().
style::Colormap readColormap(const Value& v);
// A CSS colour name or #rrggbb / #rrggbbaa (style/color.hpp).
style::Color readColor(const Value& v);
// `3px` (pixels), `0.02m` or a bare number (metres); > 0.
style::Length readLength(const Value& v);
// `auto`, `[lo, hi]`, or a map {min, max, scale}: min and max both or neither (automatic), scale
// linear or log. lo < hi, both finite, and lo > 0 on a log scale.
style::Range readRange(const Value& v);
// A label or title: one line of printable UTF-8, at most style::kMaxLabelLength code points.
std::string readLabel(const Value& v);

}  // namespace particles::scenario::detail
