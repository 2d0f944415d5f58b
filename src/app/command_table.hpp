#pragma once
// Every command of the program, one row each, in the order the main help lists them
// (docs/architecture.md, "Adding a command").

#include <span>

#include "app/command.hpp"

namespace particles::app {

extern const std::span<const AddCommand> kCommands;

}  // namespace particles::app
