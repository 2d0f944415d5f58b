#pragma once
// `--set` key paths (docs/scenarios.md, "Overrides"): `a.b[2].c` or `a.b.2.c` split into keys and list
// indices, and an override applied to a YAML tree before the loader validates it. Internal to the
// scenario loader; `Override` and `parseOverride` are in scenario.hpp.

#include <yaml-cpp/yaml.h>

#include <cstddef>
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

// Replaces or creates the node at o.path; returns the canonical key path (`forces[1].ks`).
std::string applyOverride(YAML::Node root, const Override& o, const std::string& file);

}  // namespace particles::scenario::detail
