#pragma once
// The one error of the scenario room: a scenario file, a --set or --limit option or a sweep file
// that cannot be used, with where (file, line, column, key path, option) and why. It is the public
// particles::ScenarioError (include/particles/errors.hpp): what the loader throws is what a program
// using the library catches.

#include <particles/errors.hpp>

namespace particles::scenario {

using ScenarioError = particles::ScenarioError;

}  // namespace particles::scenario
