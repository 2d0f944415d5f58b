#pragma once
// Parts of a scenario file read again after the whole file was loaded. Internal to the scenario
// loader (override_check.cpp uses it).
//
// The loader reads some parts of a file on their own: the simulation and the render sections, and
// each entry of a list (a particle, a grid, a rigid body, a force, constraint, collider or mouse
// script) against the names and points the sections before it declared. When a tree loaded whole
// has since changed in one such part only, and in nothing the other parts read of it (which
// changes those are is override_check.cpp's), reading that part again finds every error a whole
// load would find, at the cost of one entry.

#include <yaml-cpp/yaml.h>

#include <compare>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scenario/scenario.hpp"

namespace particles::scenario::detail {

class Loader;

struct FilePart {
  // In the order the loader reads them.
  enum class Kind { simulation, render, particle, grid, rigidBody, kindEntry };
  Kind kind = Kind::simulation;
  size_t section = 0;  // kindEntry: its section's place in kindSections()
  size_t index = 0;    // particle, grid, rigidBody, kindEntry: the entry's place in its list
  auto operator<=>(const FilePart&) const = default;  // the order the loader reads parts in
};

// The canonical key paths that --set replaced, each with the option it came from (Source::overridden).
using OverriddenPaths = std::vector<std::pair<std::string, std::string>>;

class PartReader {
 public:
  PartReader(std::string file, const SceneLimits& limits);
  ~PartReader();
  PartReader(PartReader&&) noexcept;
  PartReader& operator=(PartReader&&) noexcept;

  // Loads `document` whole, as loadScenarioText does once it has applied the overrides that
  // `overridden` lists. Throws ScenarioError.
  Scenario load(const YAML::Node& document, OverriddenPaths overridden);
  // After load(): the settings, or the entry `part`, read again from `document`, which has changed
  // since in that part alone (by the overrides `overridden` lists now). Throws the ScenarioError
  // that load() would throw there.
  SimulationSettings readSimulation(const YAML::Node& document, OverriddenPaths overridden);
  RenderSettings readRender(const YAML::Node& document, OverriddenPaths overridden);
  void readEntry(const YAML::Node& document, const FilePart& part, OverriddenPaths overridden);

 private:
  std::string file_;
  std::unique_ptr<SceneLimits> limits_;  // the loader keeps a reference: at one address for good
  std::unique_ptr<Loader> loader_;
};

}  // namespace particles::scenario::detail
