#include "scenario/budget.hpp"

#include <fmt/format.h>

#include <charconv>
#include <map>

#include "input/printable_text.hpp"
#include "core/grid.hpp"
#include "core/kind.hpp"
#include "scenario/references.hpp"

namespace particles::scenario::detail {

namespace {

// Type tests that hold false for a key that is absent (yaml-cpp's missing-key node throws on IsMap).
bool isMap(const YAML::Node& n) { return n.IsDefined() && n.IsMap(); }
bool isSequence(const YAML::Node& n) { return n.IsDefined() && n.IsSequence(); }
bool isScalar(const YAML::Node& n) { return n.IsDefined() && n.IsScalar(); }

// A whole number from 1 to kMaxGridSide as the loader would read it, or 0.
long long gridSide(const YAML::Node& node) {
  long long n = 0;
  if (!isScalar(node) || !YAML::convert<long long>::decode(node, n)) return 0;
  return n >= 1 && n <= kMaxGridSide ? n : 0;
}

class Tally {
 public:
  explicit Tally(const SceneLimits& limits) : limits_(limits) {}

  // Adds `n` to the total of `name` and fails at `at` when the total passes its limit.
  void add(const Value& at, long long SceneLimits::*member, std::string_view what, long long n) {
    long long& total = totals_.*member;
    total += n;
    const long long limit = limits_.*member;
    if (total <= limit) return;
    std::string_view name;
    for (const SceneLimitName& l : kSceneLimitNames) {
      if (l.member == member) name = l.name;
    }
    at.fail(fmt::format("this makes {} {}{}, more than the limit of {} (counted before anything is built); if the "
                        "scene is meant to be this large, raise the limit with --limit {}=N",
                        total, what, total == n ? "" : " in the scene so far", limit, name));
  }

 private:
  const SceneLimits& limits_;
  SceneLimits totals_{0, 0, 0, 0, 0};
};

std::string indexPath(const std::string& base, size_t i) { return fmt::format("{}[{}]", base, i); }

}  // namespace

void checkSceneBudget(const Value& root, const SceneLimits& limits) {
  Tally tally(limits);
  const YAML::Node& doc = root.node();
  auto childOf = [&](const Value& parent, const YAML::Node& node, const std::string& path) {
    return parent.child(node, path, parent.node().Mark());
  };
  auto section = [&](const char* key) -> std::optional<Value> {
    const YAML::Node node = doc[key];
    if (!isSequence(node)) return std::nullopt;
    return childOf(root, node, key);
  };

  if (const auto list = section("particles")) {
    tally.add(*list, &SceneLimits::particles, "particles", static_cast<long long>(list->node().size()));
  }
  std::map<std::string, GridIndices, std::less<>> grids;
  if (const auto list = section("grids")) {
    for (size_t i = 0; i < list->node().size(); ++i) {
      const YAML::Node grid = list->node()[i];
      if (!isMap(grid)) continue;
      const YAML::Node size = grid["size"];
      if (!isSequence(size) || size.size() != 2) continue;
      GridSpec spec;
      spec.cols = int(gridSide(size[0]));
      spec.rows = int(gridSide(size[1]));
      const Value at = childOf(*list, size, indexPath("grids", i) + ".size");
      tally.add(at, &SceneLimits::particles, "particles", static_cast<long long>(spec.cols) * spec.rows);
      if (const YAML::Node name = grid["name"]; isScalar(name)) {
        grids[name.Scalar()] = GridIndices{0, spec.cols, spec.rows};
      }
      if (const YAML::Node springs = grid["springs"]; isMap(springs)) {
        const GridSpringFamily any{0.0, 0.0, 0.0};
        if (springs["structural"].IsDefined()) spec.structural = any;
        if (springs["shear"].IsDefined()) spec.shear = any;
        if (springs["flexion"].IsDefined()) spec.flexion = any;
        tally.add(childOf(*list, springs, indexPath("grids", i) + ".springs"), &SceneLimits::springs, "springs",
                  gridSpringCount(spec));
      }
    }
  }
  if (const auto list = section("rigid_bodies")) {
    tally.add(*list, &SceneLimits::particles, "particles and rigid bodies",
              static_cast<long long>(list->node().size()));
  }

  for (const KindSection& kindSection : kindSections()) {
    const auto list = section(std::string(kindSection.key).c_str());
    if (!list) continue;
    const std::vector<const KindSpec*> kinds = kindsOf(kindSection.key);
    const std::string base(kindSection.key);
    for (size_t i = 0; i < list->node().size(); ++i) {
      const YAML::Node entry = list->node()[i];
      const Value entryAt = childOf(*list, entry, indexPath(base, i));
      tally.add(entryAt, &SceneLimits::entries, "entries in forces, constraints, colliders and mouse", 1);
      if (!isMap(entry)) continue;
      const KindSpec* kind = kinds.front();
      if (kindSection.typed) {
        const YAML::Node type = entry["type"];
        kind = isScalar(type) ? findKind(kindSection.key, type.Scalar()) : nullptr;
      }
      if (!kind) continue;
      // Each entry makes one object per point of its longest point list (springs pair two lists
      // element by element, or one point with each of a list; a wire holds each particle it lists).
      long long objects = 1;
      for (const ParamSpec& param : kind->params) {
        const bool namesPoints = param.type == ParamType::particle || param.type == ParamType::particles ||
                                 param.type == ParamType::endpoint || param.type == ParamType::endpoints;
        const YAML::Node value = namesPoints ? entry[std::string(param.key)] : YAML::Node();
        if (!value.IsDefined()) continue;
        const long long points = countPoints(value, grids);
        const Value at = childOf(entryAt, value, indexPath(base, i) + "." + std::string(param.key));
        tally.add(at, &SceneLimits::endpoints, "points named by references", points);
        objects = std::max(objects, points);
      }
      if (kindSection.key == "forces") tally.add(entryAt, &SceneLimits::springs, "springs and forces", objects);
      if (kindSection.key == "constraints") tally.add(entryAt, &SceneLimits::constraints, "constraints", objects);
    }
  }

  // The style's selections and the camera's fit hold the points they name (style_reader.cpp).
  auto countReference = [&](const Value& parent, const YAML::Node& holder, const char* key, const std::string& path) {
    const YAML::Node value = holder[key];
    if (!value.IsDefined() || (isScalar(value) && value.Scalar() == "all")) return;
    tally.add(childOf(parent, value, path + "." + key), &SceneLimits::endpoints, "points named by references",
              countPoints(value, grids));
  };
  if (const YAML::Node render = doc["render"]; isMap(render) && isMap(render["view"])) {
    countReference(root, render["view"], "fit", "render.view");
  }
  const YAML::Node style = doc["style"];
  const YAML::Node select = isMap(style) ? style["select"] : YAML::Node();
  for (size_t i = 0; isSequence(select) && i < select.size(); ++i) {
    if (!isMap(select[i])) continue;
    const std::string path = indexPath("style.select", i);
    for (const char* key : {"particles", "bodies"}) countReference(root, select[i], key, path);
  }
}

}  // namespace particles::scenario::detail

namespace particles::scenario {

void applyLimitOption(SceneLimits& limits, std::string_view text) {
  const std::string origin = fmt::format("--limit {}", text);
  std::vector<std::string_view> names;
  for (const SceneLimitName& l : kSceneLimitNames) names.push_back(l.name);
  auto bad = [&](const std::string& why) { throw ScenarioError("command line", 0, 0, "", why, origin); };
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos) bad(fmt::format("expected NAME=N with NAME one of {}", fmt::join(names, ", ")));
  const std::string_view name = text.substr(0, eq), number = text.substr(eq + 1);
  long long n = 0;
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), n);
  if (ec != std::errc() || end != number.data() + number.size() || n < 1 || n > kMaxSceneLimit) {
    bad(fmt::format("expected a whole number from 1 to {} after '=', got {}", kMaxSceneLimit,
                    input::quotedValue(number)));
  }
  for (const SceneLimitName& l : kSceneLimitNames) {
    if (l.name == name) {
      limits.*l.member = n;
      return;
    }
  }
  bad(fmt::format("unknown limit {}; expected one of {}", input::quotedValue(name), fmt::join(names, ", ")));
}

}  // namespace particles::scenario
