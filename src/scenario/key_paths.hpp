#pragma once
// `--set` key paths (docs/scenarios.md, "Overrides"): `a.b[2].c` or `a.b.2.c` split into keys and list
// indices, and an override applied to a YAML tree before the loader validates it. Internal to the
// scenario loader; `Override` and `parseOverride` are in scenario.hpp.

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"

namespace particles::scenario::detail {

// One segment of a key path; numbers are list indices.
struct PathSegment {
  std::string key;
  bool isIndex = false;
  size_t index = 0;
};

// The segments of o.path; throws ScenarioError naming o.origin when the path cannot be used.
std::vector<PathSegment> splitPath(const Override& o, const std::string& file);

// Appends `s` to a canonical key path as messages write it (`forces[1].ks`).
void appendSegment(std::string& canonical, const PathSegment& s);

// o.value as YAML; throws ScenarioError naming o.origin when it cannot be read or is empty.
YAML::Node overrideValue(const Override& o, const std::string& file);

// Replaces or creates the node at o.path; returns the canonical key path (`forces[1].ks`).
std::string applyOverride(YAML::Node root, const Override& o, const std::string& file);

// Overrides applied to a tree in place and taken back again, so that one parsed scenario serves
// many of them (override_check.hpp). Only an override that replaces one node, or adds one key to a
// map, is applied here: where applyOverride would create maps on the way (a missing key or a null
// before the last segment), or fail (a missing index, a scalar on the way), apply() changes nothing
// and the caller loads the whole file with applyOverride instead.
//
// yaml-cpp's `node = value` points the node at value's data (detail::node::set_ref), which keeps its
// mark: the tree is then the one applyOverride makes, marks and all. So that undo() can point it
// back, a slot of `saved_` is first pointed at the data it had; the slots live in the tree's memory
// after the first (yaml-cpp merges the two memories once, then shares them).
// The node that the last of `segments` names a child of, when an override there is one of those
// InPlaceOverrides applies (every segment before the last names a map or a list that is there).
std::optional<YAML::Node> parentInPlace(const YAML::Node& root, const std::vector<PathSegment>& segments);

class InPlaceOverrides {
 public:
  InPlaceOverrides(YAML::Node root, std::string file);
  ~InPlaceOverrides() { undo(); }
  InPlaceOverrides(const InPlaceOverrides&) = delete;
  InPlaceOverrides& operator=(const InPlaceOverrides&) = delete;

  // Applies `o` (its segments and value as splitPath and overrideValue give them) and returns its
  // canonical key path; nullopt, with nothing changed, when it is not one of the overrides above.
  std::optional<std::string> apply(const std::vector<PathSegment>& segments, const YAML::Node& value);
  // Takes back every override applied since the last undo(), the last first.
  void undo();

 private:
  struct Change {
    YAML::Node parent;
    PathSegment segment;
    bool added;  // a key added to a map, else a node replaced (its data in saved_[slot])
    size_t slot;
  };
  YAML::Node root_;
  std::string file_;
  YAML::Node saved_;
  std::vector<Change> changes_;
};

}  // namespace particles::scenario::detail
