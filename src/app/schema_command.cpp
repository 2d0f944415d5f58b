// `particles schema`: the scenario format as JSON Schema (draft 7) on stdout, for editors and CI
// validators; with --markdown, each kind's key table as docs/scenarios.md holds it.
#include <fmt/format.h>

#include "app/commands.hpp"
#include "core/kind.hpp"
#include "scenario/schema.hpp"

namespace particles::app {

int schemaCommand(const SchemaOptions& options) {
  if (!options.markdown) {
    fmt::print("{}", scenario::scenarioJsonSchema());
    return kOk;
  }
  for (const KindSpec* kind : registeredKinds()) {
    fmt::print("{} **{}**: {}.\n\n{}\n", kind->section, kind->type, kind->summary, scenario::kindDocsTable(*kind));
  }
  return kOk;
}

}  // namespace particles::app
