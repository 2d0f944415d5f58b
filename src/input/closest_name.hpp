#pragma once
// Suggestions for a mistyped name ("did you mean 'render'?"): a scenario's keys, types and point
// names, and the program's commands. Plain strings, so that the loader and the program share one
// spelling check without the program reading YAML.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace particles::input {

// The Levenshtein distance between a and b, ignoring ASCII case.
size_t editDistance(std::string_view a, std::string_view b);

// The candidate closest to `word` by edit distance, or empty when none is close (more than a
// third of the word, and more than two letters, wrong).
std::string closestName(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace particles::input
