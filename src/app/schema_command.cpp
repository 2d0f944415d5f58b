// `particles schema`: the scenario format as JSON Schema (draft 7) on stdout, for editors and CI
// validators; with --markdown, each kind's key table as docs/scenarios.md holds it; with --golden,
// the golden manifest's format.
#include "app/schema_command.hpp"

#include <fmt/format.h>

#include "core/kind.hpp"
#include "scenario/golden_manifest.hpp"
#include "scenario/schema.hpp"

namespace particles::app {

namespace {

void addSchemaOptions(CLI::App& command, SchemaOptions& schema) {
  CLI::Option* markdown =
      command.add_flag("--markdown", schema.markdown, "Print each kind's key table as docs/scenarios.md has it");
  command.add_flag("--golden", schema.golden, "Print the golden manifest's format (particles golden check) instead")
      ->excludes(markdown);
  command.footer(
      "Examples:\n"
      "  particles schema > scenario.schema.json\n"
      "  # then, at the top of a scenario: # yaml-language-server: $schema=scenario.schema.json\n"
      "  particles schema --markdown\n"
      "  particles schema --golden > golden.schema.json   # for golden manifests (golden/README.md)\n");
}

int schemaCommand(const SchemaOptions& options) {
  if (options.golden) {
    fmt::print("{}", scenario::goldenManifestJsonSchema());
    return kOk;
  }
  if (!options.markdown) {
    fmt::print("{}", scenario::scenarioJsonSchema());
    return kOk;
  }
  for (const KindSpec* kind : registeredKinds()) {
    fmt::print("{} **{}**: {}.\n\n{}\n", kind->section, kind->type, kind->summary, scenario::kindDocsTable(*kind));
  }
  return kOk;
}

}  // namespace

const CommandDescriptor<SchemaOptions> kSchemaCommand = {
    .name = "schema",
    .summary = "Print the scenario format as JSON Schema (draft 7), for editors and validators",
    .addOptions = addSchemaOptions,
    .run = schemaCommand,
};

}  // namespace particles::app
