#pragma once
// A sweep's `scale` parameters (docs/sweeps.md): factors on a value the scenario itself writes.

#include <string>
#include <string_view>

namespace particles::scenario {

// The value at key path `path` (as --set writes it) of a scenario's text with every number in it
// multiplied by `factor`, as YAML flow text: a sweep's `scale` parameter. Throws ScenarioError
// naming the scenario file when the path is not in the file or holds anything but numbers.
std::string scaledValueAt(std::string_view text, const std::string& file, const std::string& path, double factor);

}  // namespace particles::scenario
