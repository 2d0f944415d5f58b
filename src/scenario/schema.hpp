#pragma once
// The scenario format described for machines and for people, from the same descriptions the
// loader validates with: the fixed sections' settings structs and limits (scenario.hpp) and each
// registered kind's ParamSpecs (core/kind.hpp).
//   - scenarioJsonSchema(): JSON Schema (draft 7) of a scenario file, for editors (completion,
//     validation: `# yaml-language-server: $schema=…` at the top of a file) and for CI checks.
//   - kindDocsTable(): a kind's key table as docs/scenarios.md prints it; a test checks that the
//     docs hold exactly these tables, so documented defaults and ranges cannot drift.

#include <string>

#include "core/kind.hpp"

namespace particles::scenario {

// Pretty-printed JSON (two-space indent, keys in a fixed order), ending in a newline.
std::string scenarioJsonSchema();

// | key | type | unit | default | allowed | rows, columns padded to line up, ending in a newline.
std::string kindDocsTable(const KindSpec& kind);

}  // namespace particles::scenario
