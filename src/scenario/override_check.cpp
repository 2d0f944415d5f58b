#include "scenario/override_check.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <utility>

#include "core/kind.hpp"
#include "scenario/key_paths.hpp"
#include "scenario/part_reader.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario {

namespace {

using detail::FilePart;
using detail::PathSegment;

bool keyAt(const std::vector<PathSegment>& s, size_t k) {
  return k < s.size() && !s[k].isIndex;
}

bool namesPoints(ParamType type) {
  return type == ParamType::particle || type == ParamType::particles || type == ParamType::endpoint ||
         type == ParamType::endpoints;
}

// The entry SECTION[i] of the tree, or an undefined node.
YAML::Node entryAt(const YAML::Node& root, const std::string& section, size_t i) {
  const YAML::Node list = root[section];
  return list.IsSequence() && i < list.size() ? list[i] : YAML::Node();
}

// The part that an override at `s` changes alone, if it changes one alone: what no other part reads
// and the scene's budget does not count. The other parts read the names and points the fixed
// sections declare (a name, a particle's or body's position and angle, a grid's name, origin, size
// and spacing); budget.cpp counts lists' lengths, grid sizes and spring families, and each kind
// entry's type and the points it names. So a particle's or body's mass and velocities, a grid's
// mass and its spring families' numbers, a kind entry's keys other than its type and its points,
// and the simulation and render settings (their sections' own readers alone read them) change one
// part; anything else may change what any part reads.
std::optional<FilePart> partChanged(const YAML::Node& root, const std::vector<PathSegment>& s) {
  using Kind = FilePart::Kind;
  if (!detail::parentInPlace(root, s) || !keyAt(s, 0)) return std::nullopt;
  const std::string& section = s[0].key;
  if (section == "simulation") return FilePart{Kind::simulation};
  if (section == "render") {
    // Except render.view.fit: the points it names count toward the scene's budget.
    const bool mayChangeFit =
        s.size() < 2 || (keyAt(s, 1) && s[1].key == "view" && (s.size() < 3 || (keyAt(s, 2) && s[2].key == "fit")));
    if (mayChangeFit) return std::nullopt;
    return FilePart{Kind::render};
  }
  // Below, a key of entry i of a list: SECTION[i].KEY…
  if (s.size() < 3 || !s[1].isIndex || !keyAt(s, 2)) return std::nullopt;
  const size_t i = s[1].index;
  const std::string& key = s[2].key;
  if (section == "particles" && (key == "mass" || key == "vel")) return FilePart{Kind::particle, 0, i};
  if (section == "rigid_bodies" && (key == "mass" || key == "vel" || key == "omega")) {
    return FilePart{Kind::rigidBody, 0, i};
  }
  if (section == "grids") {
    if (key == "mass") return FilePart{Kind::grid, 0, i};
    // A family that is there before and after: the budget counts the grid's springs by them.
    if (key != "springs" || !keyAt(s, 3)) return std::nullopt;
    const std::string& family = s[3].key;
    if (family != "structural" && family != "shear" && family != "flexion") return std::nullopt;
    const YAML::Node springs = entryAt(root, section, i)["springs"];
    if (!springs.IsMap() || !springs[family].IsMap()) return std::nullopt;
    return FilePart{Kind::grid, 0, i};
  }
  const std::vector<KindSection>& sections = kindSections();
  for (size_t k = 0; k < sections.size(); ++k) {
    if (sections[k].key != section) continue;
    const YAML::Node entry = entryAt(root, section, i);
    if (!entry.IsMap() || key == "type") return std::nullopt;
    const KindSpec* kind = kindsOf(section).front();
    if (sections[k].typed) {
      const YAML::Node type = entry["type"];
      kind = type.IsScalar() ? findKind(section, type.Scalar()) : nullptr;
    }
    if (!kind) return std::nullopt;
    if (const ParamSpec* param = kind->param(key); param && namesPoints(param->type)) return std::nullopt;
    return FilePart{Kind::kindEntry, k, i};
  }
  return std::nullopt;
}

}  // namespace

struct OverrideChecker::Tree {
  // An override's path: its segments and the part an override there changes alone.
  struct Path {
    std::vector<PathSegment> segments;
    std::optional<FilePart> part;
  };

  std::string text, file;
  std::vector<Override> fixed;
  SceneLimits limits;
  detail::OverriddenPaths fixedPaths;
  // A node repeated by an alias is at two key paths, in two parts: an override of one changes the
  // other, which a whole load reads (and may name in its error), so every override loads it whole.
  bool aliases = false;
  YAML::Node root;  // the text with the fixed overrides applied
  detail::PartReader reader;
  detail::InPlaceOverrides inPlace;
  ScenarioSettings base;
  // Each path read before: a sweep has few, each with many values.
  std::map<std::string, Path> paths;
  // The parts read with a list of overrides, which passed, by partKey(); the settings the simulation
  // and render sections were read as.
  std::set<std::string> passed;
  std::map<std::string, SimulationSettings> simulations;
  std::map<std::string, RenderSettings> renders;
  // Settings under overrides that are not of one part, by their paths and values.
  std::map<std::string, ScenarioSettings> wholeSettings;

  Tree(std::string text_, std::string file_, std::vector<Override> fixed_, const SceneLimits& limits_)
      : text(std::move(text_)),
        file(std::move(file_)),
        fixed(std::move(fixed_)),
        limits(limits_),
        root(loadRoot()),
        reader(file, limits),
        inPlace(root, file) {
    const Scenario loaded = reader.load(root, fixedPaths);
    base = {loaded.simulation, loaded.render};
  }

  // The tree as loadScenarioText makes it before reading it: the document, a map, with the fixed
  // overrides applied.
  YAML::Node loadRoot() {
    YAML::Node document =
        detail::loadOneDocument(text, file, &aliases, detail::NodeLimit::scenario(std::uintmax_t(limits.nodes)));
    if (!document.IsMap()) {
      const YAML::Mark m = document.Mark();
      throw ScenarioError(file, m.line + 1, m.column + 1, "", "expected a scenario (a map of keys such as 'name')");
    }
    for (const Override& o : fixed) fixedPaths.emplace_back(detail::applyOverride(document, o, file), o.origin);
    return document;
  }

  // The override's path: read before, or read now (throwing what applyOverride throws for it).
  const Path& pathOf(const Override& o) {
    if (const auto it = paths.find(o.path); it != paths.end()) return it->second;
    Path p{detail::splitPath(o, file), std::nullopt};
    if (!aliases) p.part = partChanged(root, p.segments);
    return paths.emplace(o.path, std::move(p)).first->second;
  }

  const Path* pathBefore(const Override& o) const {
    const auto it = paths.find(o.path);
    return it == paths.end() ? nullptr : &it->second;
  }

  ScenarioSettings whole(std::span<const Override> overrides) {
    std::vector<Override> all = fixed;
    all.insert(all.end(), overrides.begin(), overrides.end());
    const Scenario loaded = loadScenarioText(text, file, all, limits);
    return {loaded.simulation, loaded.render};
  }

  // The overrides of `overrides` that change `part`, as one key: the part, then each path and value.
  static std::string partKey(const FilePart& part, std::span<const Override> overrides,
                             const std::vector<const Path*>& prepared) {
    std::string key = fmt::format("{} {} {}", int(part.kind), part.section, part.index);
    for (size_t k = 0; k < overrides.size(); ++k) {
      if (prepared[k]->part == part) key += fmt::format("\n{}={}", overrides[k].path, overrides[k].value);
    }
    return key;
  }

  // The parts `overrides` change (all of one part each, prepared before), each with its key.
  static std::map<FilePart, std::string> partsOf(std::span<const Override> overrides,
                                                 const std::vector<const Path*>& prepared) {
    std::map<FilePart, std::string> parts;
    for (const Path* p : prepared) parts.emplace(*p->part, std::string());
    for (auto& [part, key] : parts) key = partKey(part, overrides, prepared);
    return parts;
  }

  // The settings under overrides whose parts were all read before, from those readings.
  ScenarioSettings settingsOf(const std::map<FilePart, std::string>& parts) const {
    ScenarioSettings s = base;
    for (const auto& [part, key] : parts) {
      if (part.kind == FilePart::Kind::simulation) s.simulation = simulations.at(key);
      if (part.kind == FilePart::Kind::render) s.render = renders.at(key);
    }
    return s;
  }

  // Applies `overrides` in place, reads each part they change that was not read before with the
  // same overrides, in the order the loader reads parts (so that the first error is the one a
  // whole load would throw: the parts they do not change read as before), and takes them back.
  ScenarioSettings readParts(std::span<const Override> overrides) {
    std::vector<const Path*> ready;
    detail::OverriddenPaths overridden = fixedPaths;
    struct Undo {
      detail::InPlaceOverrides& inPlace;
      ~Undo() { inPlace.undo(); }
    } undo{inPlace};
    for (const Override& o : overrides) {
      const Path& p = pathOf(o);
      const YAML::Node value = detail::overrideValue(o, file);
      if (!p.part) return whole(overrides);
      const std::optional<std::string> canonical = inPlace.apply(p.segments, value);
      // An earlier override of the list changed the path's way (a map it replaced with a number).
      if (!canonical) return whole(overrides);
      overridden.emplace_back(*canonical, o.origin);
      ready.push_back(&p);
    }
    const std::map<FilePart, std::string> parts = partsOf(overrides, ready);
    for (const auto& [part, key] : parts) {
      if (passed.count(key)) continue;
      if (part.kind == FilePart::Kind::simulation) {
        simulations[key] = reader.readSimulation(root, overridden);
      } else if (part.kind == FilePart::Kind::render) {
        renders[key] = reader.readRender(root, overridden);
      } else {
        reader.readEntry(root, part, overridden);
      }
      passed.insert(key);
    }
    return settingsOf(parts);
  }

  ScenarioSettings check(std::span<const Override> overrides) {
    // Read before (each value too, in the parts' keys): nothing to apply.
    std::vector<const Path*> ready;
    for (const Override& o : overrides) {
      const Path* p = pathBefore(o);
      if (!p || !p->part) break;
      ready.push_back(p);
    }
    if (ready.size() == overrides.size()) {
      const std::map<FilePart, std::string> parts = partsOf(overrides, ready);
      if (std::all_of(parts.begin(), parts.end(), [&](const auto& p) { return passed.count(p.second) > 0; })) {
        return settingsOf(parts);
      }
    }
    return readParts(overrides);
  }

  ScenarioSettings checkTogether(std::span<const Override> overrides) {
    std::vector<Override> ofOnePart, ofSettings;
    bool settingsElsewhere = false;
    for (const Override& o : overrides) {
      const Path& p = pathOf(o);
      if (p.part) ofOnePart.push_back(o);
      if (keyAt(p.segments, 0) && (p.segments[0].key == "simulation" || p.segments[0].key == "render")) {
        ofSettings.push_back(o);
        // Not of one part: a path through a section the file does not have, or a file with aliases.
        settingsElsewhere = settingsElsewhere || !p.part;
      }
    }
    const ScenarioSettings s = check(ofOnePart);
    if (!settingsElsewhere) return s;
    // Only those two sections set the settings: the file loaded whole with the overrides there
    // alone, once for each distinct list of them.
    std::string key;
    for (const Override& o : ofSettings) key += o.path + "=" + o.value + "\n";
    if (const auto it = wholeSettings.find(key); it != wholeSettings.end()) return it->second;
    return wholeSettings[key] = whole(ofSettings);
  }
};

OverrideChecker::OverrideChecker(std::string text, std::string file, std::vector<Override> fixed,
                                 const SceneLimits& limits)
    : tree_(std::make_unique<Tree>(std::move(text), std::move(file), std::move(fixed), limits)) {}
OverrideChecker::~OverrideChecker() = default;
OverrideChecker::OverrideChecker(OverrideChecker&&) noexcept = default;
OverrideChecker& OverrideChecker::operator=(OverrideChecker&&) noexcept = default;

ScenarioSettings OverrideChecker::check(std::span<const Override> overrides) {
  return tree_->check(overrides);
}

ScenarioSettings OverrideChecker::checkTogether(std::span<const Override> overrides) {
  return tree_->checkTogether(overrides);
}

}  // namespace particles::scenario
