#pragma once
// A sweep's `scale` parameters (docs/sweeps.md): factors on a value the scenario itself writes.

#include <string>
#include <string_view>
#include <vector>

namespace particles::scenario {

// The value at key path `path` (as --set writes it) of a scenario's text, read once, and then any
// number of times scaled: a sweep's `scale` parameter over all its values.
class ScaledValue {
 public:
  // Throws ScenarioError naming the scenario file when the path is not in the file or holds
  // anything but numbers (or lists of them).
  ScaledValue(std::string_view text, const std::string& file, const std::string& path);

  // The value with every number in it multiplied by `factor`, as YAML flow text (`[12.5, 0.5]`).
  std::string times(double factor) const;

 private:
  // The value's text around its numbers: pieces_[k] before numbers_[k], the last piece after them.
  std::vector<std::string> pieces_;
  std::vector<double> numbers_;
};

}  // namespace particles::scenario
