#include "scenario/scaled_value.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <vector>

#include "scenario/key_paths.hpp"
#include "scenario/scenario_error.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario {

namespace {

// `node` with every number times `factor`, in YAML flow form; throws `fail` at anything else.
template <class Fail>
std::string scaledFlow(const YAML::Node& node, double factor, const Fail& fail) {
  if (node.IsSequence()) {
    std::vector<std::string> items;
    for (const YAML::Node& item : node) items.push_back(scaledFlow(item, factor, fail));
    return fmt::format("[{}]", fmt::join(items, ", "));
  }
  double x = 0.0;
  if (!node.IsScalar() || node.Tag() == "!" || !YAML::convert<double>::decode(node, x) || !std::isfinite(x)) {
    fail(node.IsMap() ? std::string("holds a map, not numbers")
                      : fmt::format("holds '{}', not a number", node.IsScalar() ? node.Scalar() : ""));
  }
  return detail::formatNumber(x * factor);
}

}  // namespace

std::string scaledValueAt(std::string_view text, const std::string& file, const std::string& path, double factor) {
  const Override o{path, "", ""};
  const std::vector<detail::PathSegment> segments = detail::splitPath(o, file);
  YAML::Node cur = detail::loadOneDocument(std::string(text), file);
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
  return scaledFlow(cur, factor, [&](const std::string& why) {
    throw ScenarioError(file, m.is_null() ? 0 : m.line + 1, m.is_null() ? 0 : m.column + 1, canonical,
                        fmt::format("cannot scale it: it {}", why));
  });
}

}  // namespace particles::scenario
