#include "scenario/scaled_value.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

#include "input/printable_text.hpp"
#include "scenario/key_paths.hpp"
#include "scenario/scenario_error.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario {

namespace {

// Splits `node` into the text around its numbers and the numbers, in YAML flow form; throws
// `fail` at anything but numbers and lists of them.
template <class Fail>
void splitNumbers(const YAML::Node& node, std::vector<std::string>& pieces, std::vector<double>& numbers,
                  const Fail& fail) {
  if (node.IsSequence()) {
    pieces.back() += "[";
    for (size_t i = 0; i < node.size(); ++i) {
      if (i > 0) pieces.back() += ", ";
      splitNumbers(node[i], pieces, numbers, fail);
    }
    pieces.back() += "]";
    return;
  }
  double x = 0.0;
  if (!node.IsScalar() || node.Tag() == "!" || !YAML::convert<double>::decode(node, x) || !std::isfinite(x)) {
    fail(node.IsMap()
             ? std::string("holds a map, not numbers")
             : fmt::format("holds {}, not a number", input::quotedValue(node.IsScalar() ? node.Scalar() : "")));
  }
  numbers.push_back(x);
  pieces.emplace_back();
}

}  // namespace

ScaledValue::ScaledValue(std::string_view text, const std::string& file, const std::string& path) : pieces_(1) {
  const Override o{path, "", ""};
  const std::vector<detail::PathSegment> segments = detail::splitPath(o, file);
  YAML::Node cur = detail::loadOneDocument(std::string(text), file, nullptr,
                                           detail::NodeLimit::scenario(std::uintmax_t(SceneLimits{}.nodes)));
  std::string canonical;
  for (const detail::PathSegment& s : segments) {
    detail::appendSegment(canonical, s);
    const bool present = s.isIndex ? cur.IsSequence() && s.index < cur.size() : cur.IsMap() && cur[s.key].IsDefined();
    if (!present) {
      throw ScenarioError(file, 0, 0, canonical,
                          "not in the file: a scaled parameter multiplies the value the scenario writes there");
    }
    YAML::Node next = s.isIndex ? cur[s.index] : cur[s.key];
    cur.reset(next);
  }
  const YAML::Mark m = cur.Mark();
  splitNumbers(cur, pieces_, numbers_, [&](const std::string& why) {
    throw ScenarioError(file, m.is_null() ? 0 : m.line + 1, m.is_null() ? 0 : m.column + 1, canonical,
                        fmt::format("cannot scale it: it {}", why));
  });
}

std::string ScaledValue::times(double factor) const {
  std::string text = pieces_.front();
  for (size_t k = 0; k < numbers_.size(); ++k) text += detail::formatNumber(numbers_[k] * factor) + pieces_[k + 1];
  return text;
}

}  // namespace particles::scenario
