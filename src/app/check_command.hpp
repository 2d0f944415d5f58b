#pragma once
// `particles check SCENARIO` (docs/physics.md §12): loads and validates a scenario without
// simulating it, and prints what it holds.
//
// Exit codes: 0 valid; 2 bad input (the message names the file, line, column and key).

#include "app/command.hpp"

namespace particles::app {

struct CheckOptions {
  CommonOptions common;
};

extern const CommandDescriptor<CheckOptions> kCheckCommand;

}  // namespace particles::app
