#pragma once
// `particles schema [--markdown]`: the scenario format as JSON Schema (draft 7) on stdout, for
// editors and CI validators; with --markdown, each kind's key table as docs/scenarios.md holds it.
//
// Exit code: 0.

#include "app/command.hpp"

namespace particles::app {

struct SchemaOptions {
  bool markdown = false;  // the docs' key tables instead of JSON Schema
};

extern const CommandDescriptor<SchemaOptions> kSchemaCommand;

}  // namespace particles::app
