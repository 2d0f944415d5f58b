#pragma once
// One scenario checked against many --set overrides: a sweep's values (docs/sweeps.md, "Checked
// before any job runs"). Loading a scenario whole for each value cost up to a large scene's whole
// parse per value, mostly yaml-cpp's (bench/README.md, "Planning a sweep", has the numbers). The
// file is parsed and loaded once; an override then costs what reading the one part of
// the file it changes costs (part_reader.hpp): a force's `ks`, a grid's spring stiffness or mass, a
// particle's mass or velocity, a setting of the simulation or render section. An override that
// changes what other parts read (a grid's size or name, a particle's position, a reference, an
// entry's type: names, points and the scene's budget) may make any part fail, so for it the file is
// loaded whole again.

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"

namespace particles::scenario {

// The settings a scenario loads with (what a split render counts its frames from).
struct ScenarioSettings {
  SimulationSettings simulation;
  RenderSettings render;
};

class OverrideChecker {
 public:
  // Parses `text` and loads it with `fixed` applied, once. Throws the ScenarioError
  // loadScenarioText(text, file, fixed, limits) throws.
  OverrideChecker(std::string text, std::string file, std::vector<Override> fixed, const SceneLimits& limits = {});
  ~OverrideChecker();
  OverrideChecker(OverrideChecker&&) noexcept;
  OverrideChecker& operator=(OverrideChecker&&) noexcept;

  // Throws the ScenarioError that loadScenarioText(text, file, fixed + overrides, limits) throws,
  // if any; returns the settings the scenario loads with. Each part of the file is read once per
  // distinct list of the overrides that change it: a part it read before is not read again.
  ScenarioSettings check(std::span<const Override> overrides);

  // A job's overrides: those that change one part alone checked together there (as check() does:
  // once per distinct combination), the others left out, since each was checked alone and checking
  // them together would load the whole file for every job. Returns the settings under all of them.
  ScenarioSettings checkTogether(std::span<const Override> overrides);

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace particles::scenario
