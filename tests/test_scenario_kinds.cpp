// Every registered kind (core/kinds.cpp) is documented, described by the schema and validated by
// the loader from its one description (core/kind.hpp): docs/scenarios.md holds each kind's key
// table exactly as `particles schema --markdown` prints it, docs/scenario.schema.json is what
// `particles schema` prints (and docs/golden-manifest.schema.json what `particles schema --golden`
// prints), and every bound a kind declares is the bound the loader enforces.
#include <doctest/doctest.h>

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <string>

#include "core/kind.hpp"
#include "scenario/golden_manifest.hpp"
#include "scenario/scenario.hpp"
#include "scenario/schema.hpp"

using namespace particles;
using namespace particles::scenario;

namespace {

std::string readSource(const std::string& relative) {
  std::ifstream in(std::string(PARTICLES_SOURCE_DIR) + "/" + relative, std::ios::binary);
  REQUIRE_MESSAGE(in, "cannot read " << relative);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Two particles p0 and p1 to refer to; the entry's section holds one entry.
std::string scenarioWith(const KindSpec& kind, const std::string& entry) {
  return fmt::format("name: t\nparticles:\n  - {{name: p0, pos: [0, 0]}}\n  - {{name: p1, pos: [1, 0.5]}}\n{}:\n  - {}\n",
                     kind.section, entry);
}

// A value inside the bounds of a number parameter.
double validNumber(const ParamSpec& p) {
  if (p.min && p.max) return 0.5 * (p.min->value + p.max->value);
  if (p.min) return p.min->value + 1.0;
  if (p.max) return p.max->value - 1.0;
  return 1.0;
}

// An entry with every required key (and one of each either-or pair) set to a valid value, plus
// `extraKey: extraValue` when given.
std::string minimalEntry(const KindSpec& kind, const std::string& extraKey = {}, const std::string& extraValue = {}) {
  const bool typed = kind.section != "mouse";
  std::string entry = typed ? fmt::format("{{type: {}", kind.type) : "{";
  bool first = !typed;
  int nextParticle = 0;
  for (const ParamSpec& p : kind.params) {
    const bool eitherOrFirst = !p.insteadOf.empty() && kind.param(p.insteadOf) > &p;
    if (p.key == extraKey || !(p.required || eitherOrFirst)) continue;
    std::string value;
    switch (p.type) {
      case ParamType::number: value = fmt::format("{}", validNumber(p)); break;
      case ParamType::vec2: value = "[1, 0.5]"; break;
      case ParamType::particle:
      case ParamType::particles:
      case ParamType::endpoint:
      case ParamType::endpoints: value = fmt::format("p{}", nextParticle++ % 2); break;
      case ParamType::path: value = "[[0, 0], [1, 1]]"; break;
    }
    entry += fmt::format("{}{}: {}", first ? "" : ", ", p.key, value);
    first = false;
  }
  if (!extraKey.empty()) entry += fmt::format("{}{}: {}", first ? "" : ", ", extraKey, extraValue);
  return entry + "}";
}

std::string keyPath(const KindSpec& kind, std::string_view key) { return fmt::format("{}[0].{}", kind.section, key); }

}  // namespace

TEST_CASE("docs/scenarios.md holds every registered kind's key table, as the kind describes it") {
  const std::string docs = readSource("docs/scenarios.md");
  REQUIRE(registeredKinds().size() == 9);
  for (const KindSpec* kind : registeredKinds()) {
    CAPTURE(kind->type);
    const std::string table = kindDocsTable(*kind);
    // On failure: paste the table printed here (or `particles schema --markdown`) into the docs.
    CHECK_MESSAGE(docs.find(table) != std::string::npos, "docs/scenarios.md lacks this table for '"
                                                             << kind->type << "':\n" << table);
    if (kind->section != "mouse") CHECK(docs.find(fmt::format("**{}**:", kind->type)) != std::string::npos);
  }
}

TEST_CASE("docs/scenario.schema.json is what `particles schema` prints") {
  // On failure: particles schema > docs/scenario.schema.json
  CHECK(readSource("docs/scenario.schema.json") == scenarioJsonSchema());
}

TEST_CASE("docs/golden-manifest.schema.json is what `particles schema --golden` prints") {
  // On failure: particles schema --golden > docs/golden-manifest.schema.json
  CHECK(readSource("docs/golden-manifest.schema.json") == goldenManifestJsonSchema());
}

TEST_CASE("every kind loads from its required keys alone, and rejects a key it does not declare") {
  for (const KindSpec* kind : registeredKinds()) {
    CAPTURE(kind->type);
    const std::string yaml = scenarioWith(*kind, minimalEntry(*kind));
    CAPTURE(yaml);
    CHECK_NOTHROW(loadScenarioText(yaml, "t.yaml"));
    try {
      loadScenarioText(scenarioWith(*kind, minimalEntry(*kind, "no_such_key", "1")), "t.yaml");
      FAIL("an undeclared key was accepted");
    } catch (const ScenarioError& e) {
      CHECK(e.keyPath() == keyPath(*kind, "no_such_key"));
      CHECK(e.message().find("unknown key") != std::string::npos);
    }
  }
}

TEST_CASE("every bound a kind declares is the bound the loader enforces") {
  int checked = 0;
  for (const KindSpec* kind : registeredKinds()) {
    for (const ParamSpec& p : kind->params) {
      if (p.type != ParamType::number) continue;
      CAPTURE(kind->type);
      CAPTURE(p.key);
      auto load = [&](double x) {
        return loadScenarioText(scenarioWith(*kind, minimalEntry(*kind, std::string(p.key), fmt::format("{}", x))),
                                "t.yaml");
      };
      auto rejects = [&](double x) {
        CAPTURE(x);
        try {
          load(x);
        } catch (const ScenarioError& e) {
          CHECK(e.keyPath() == keyPath(*kind, p.key));
          return true;
        }
        return false;
      };
      for (const auto& [bound, outward] : {std::pair{p.min, -1.0}, std::pair{p.max, 1.0}}) {
        if (!bound) continue;
        const double step = std::max(1e-9, std::abs(bound->value) * 1e-9);
        CHECK(rejects(bound->value + outward * step));            // just outside
        CHECK(rejects(bound->value) == !bound->inclusive);        // on the bound
        CHECK_FALSE(rejects(bound->value - outward * step));      // just inside
        ++checked;
      }
      if (!p.required && p.defaultNumber) CHECK_FALSE(rejects(*p.defaultNumber));  // the default is allowed
    }
  }
  CHECK(checked >= 14);  // ks, kd of every constraint, k and damping of every collider, …
}
