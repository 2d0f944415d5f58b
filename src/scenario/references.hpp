#pragma once
// References to points in a scenario (docs/physics.md §11), resolved against the names declared so far:
//   bob                a particle by name (or, where bodies are allowed, a rigid body's centre;
//                      where lists are allowed, a whole grid)
//   cloth[3][4]        a grid particle; `*` for a whole row or column where a list is accepted,
//                      negative indices count from the end (cloth[-1][0]: bottom-left)
//   link0@[0.2, 0.05]  an anchor on a rigid body, in body coordinates (metres)
//   #7                 particle number 7 (as --trace names unnamed particles)
// Internal to the scenario loader.

#include <map>
#include <string>
#include <vector>

#include "core/endpoint.hpp"
#include "core/grid.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario::detail {

// The particles, grids and rigid bodies declared so far, by the name each was given.
class NamedObjects {
 public:
  enum class Kind { particle, grid, body };
  struct Entry {
    Kind kind;
    int index = -1;    // particle or body index
    GridIndices grid;  // for a grid
    int line = 0;      // where it was declared, for duplicate-name messages
  };

  // Fails at `at` when the name is malformed or already taken (by any kind of object).
  void add(const Value& at, const std::string& name, Entry entry);
  const Entry* find(const std::string& name) const;
  std::vector<std::string> names() const;

  int numParticles = 0;  // particles declared so far (for #index)

 private:
  std::map<std::string, Entry, std::less<>> entries_;
};

enum class PointKind {
  particle,  // particles only (constraints act on particles)
  endpoint,  // particles or rigid-body anchors (springs, mouse)
};

// Resolves `value` (a reference string, or with allowList also a YAML list of them) to points.
// A single reference (allowList false) must name exactly one point.
std::vector<Endpoint> resolvePoints(const Value& value, const NamedObjects& names, PointKind kind, bool allowList);

// How many points `value` (a reference or a list of them) names once expanded, without checking or
// building anything: whole grids and `*` rows or columns count by the sizes in `grids`; anything
// else, malformed references included, counts one (resolvePoints reports those).
long long countPoints(const YAML::Node& value, const std::map<std::string, GridIndices, std::less<>>& grids);

}  // namespace particles::scenario::detail
