#pragma once
// What a particles::Scenario holds (include/particles/scenario.hpp): the scenario's text, the
// style and values set on it, which a Simulation loads again into its own System, and the scenario
// as last loaded, for its settings. Shared by scenario.cpp and simulation.cpp.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <particles/scenario.hpp>

#include "scenario/scenario.hpp"

namespace particles {

struct Scenario::Impl {
  std::string text;   // the YAML as read
  std::string file;   // the path or label, for messages
  std::vector<scenario::Override> overrides;  // set()'s values, in order
  // setStyle()'s, as a style file (`render --style FILE`): merged before the overrides.
  std::optional<scenario::StyleFile> style;
  // Loaded from text with overrides; never changed once made, so copies of a Scenario share it.
  std::shared_ptr<const scenario::Scenario> loaded;

  // The scenario loaded afresh from text with overrides: the System a Simulation steps.
  scenario::Scenario load() const;
  // A scenario's Impl with its text loaded (ScenarioError when it cannot be).
  static std::unique_ptr<Impl> loadedFrom(std::string text, std::string file);
};

}  // namespace particles
