#pragma once
// The scene budget (SceneLimits): what a scenario file would build, counted from its YAML tree
// before anything is built. Internal to the scenario loader; SceneLimits and `--limit`
// (applyLimitOption, defined in budget.cpp) are in scenario.hpp.

#include "scenario/scenario.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario::detail {

// Counts particles, springs, constraints, endpoints and kind entries in document order and fails at
// the first value that takes a total past its limit, saying how many and how to raise the limit.
// Values the loader will reject anyway (wrong types, unknown names) count as little as possible:
// their errors are the loader's to report, with its own words.
void checkSceneBudget(const Value& root, const SceneLimits& limits);

}  // namespace particles::scenario::detail
