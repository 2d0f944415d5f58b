#pragma once
// `particles schema [--markdown | --golden]`: the scenario format as JSON Schema (draft 7) on stdout,
// for editors and CI validators; with --markdown, each kind's key table as docs/scenarios.md holds
// it; with --golden, the golden manifest's format (`particles golden check`) as JSON Schema.
//
// Exit code: 0.

#include "app/command.hpp"

namespace particles::app {

struct SchemaOptions {
  bool markdown = false;  // the docs' key tables instead of JSON Schema
  bool golden = false;    // the golden manifest's schema instead of the scenario's
};

extern const CommandDescriptor<SchemaOptions> kSchemaCommand;

}  // namespace particles::app
