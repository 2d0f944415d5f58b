// The scene budget (SceneLimits, docs/scenarios.md "Limits"): totals counted from the file before
// anything is built. The counts must be exact for real scenes (a limit equal to what the scene
// builds passes, one less fails), and a few hundred bytes that would expand to hundreds of millions
// of springs are refused at the offending key without building the grid first.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <filesystem>
#include <string>

#include "core/forces/damped_spring_force.hpp"
#include "core/grid.hpp"
#include "core/system.hpp"
#include "input/text_file.hpp"
#include "sanitizer.hpp"
#include "scenario/scenario.hpp"
#include "source_tree.hpp"

using namespace particles;
using namespace particles::scenario;

using particles::test::kScenarios;

namespace {


struct BudgetRefusal {
  int line = -1;
  std::string keyPath, message;
};

// The ScenarioError of loading `yaml` under `limits`, or a failed check when it loads.
BudgetRefusal refusalOf(const std::string& yaml, const SceneLimits& limits) {
  try {
    loadScenarioText(yaml, "b.yaml", {}, limits);
  } catch (const ScenarioError& e) {
    return {e.line(), e.keyPath(), e.message()};
  }
  FAIL("expected a ScenarioError for:\n" << yaml);
  return {};
}

// What a loaded scene holds, in the budget's categories.
SceneLimits countsOf(const System& system) {
  SceneLimits n{0, 0, 0, 0, 0, 0};  // endpoints, entries and nodes are not counted from the system
  n.particles = system.layout().numParticles + system.layout().numBodies;
  for (const auto& f : system.forces()) {
    if (f->kind() != "mouse") n.springs += static_cast<long long>(f->count());
  }
  n.constraints = static_cast<long long>(system.constraints().size());
  return n;
}

}  // namespace

TEST_CASE("scene budget: gridSpringCount counts exactly the springs addGrid adds") {
  const GridSpringFamily family{10.0, 10.0, 0.1};
  for (const auto& [cols, rows] : {std::pair{1, 1}, {1, 5}, {5, 1}, {2, 2}, {3, 2}, {7, 4}}) {
    for (int families = 0; families < 8; ++families) {
      GridSpec spec;
      spec.cols = cols;
      spec.rows = rows;
      if (families & 1) spec.structural = family;
      if (families & 2) spec.shear = family;
      if (families & 4) spec.flexion = family;
      SystemBuilder builder;
      DampedSpringForce springs;
      addGrid(builder, springs, spec);
      CAPTURE(cols);
      CAPTURE(rows);
      CAPTURE(families);
      CHECK(gridSpringCount(spec) == static_cast<long long>(springs.size()));
    }
  }
}

TEST_CASE("scene budget: each demo loads at limits equal to what it builds and is refused one below") {
  for (const auto& entry : std::filesystem::directory_iterator(kScenarios)) {
    if (entry.path().extension() != ".yaml") continue;
    // Under ASan + UBSan (build-asan) not the million-particle cloth (most of this case's time
    // there): the same loader and counts as the other demos; its own test case loads it there once.
    if (particles::test::kUnderAddressSanitizer && entry.path().stem() == "cloth_million") continue;
    CAPTURE(entry.path().filename().string());
    const SceneLimits built = countsOf(loadScenarioFile(entry.path()).system);
    // Every limit at once at what the demo builds (one load: each limit is checked on its own, so
    // this holds each of them at its exact value), then each one below it, alone.
    SceneLimits exact;
    for (const SceneLimitName& l : kSceneLimitNames) {
      if (built.*l.member != 0) exact.*l.member = built.*l.member;
    }
    CHECK_NOTHROW(loadScenarioFile(entry.path(), {}, particles::input::kDefaultMaxInputMiB, exact));
    for (const SceneLimitName& l : kSceneLimitNames) {
      const long long n = built.*l.member;
      if (n == 0) continue;
      CAPTURE(l.name);
      SceneLimits below;
      below.*l.member = n - 1;
      const std::string raise = fmt::format("--limit {}=N", l.name);
      CHECK_THROWS_WITH_AS(loadScenarioFile(entry.path(), {}, particles::input::kDefaultMaxInputMiB, below),
                           doctest::Contains(raise.c_str()), ScenarioError);
    }
  }
}

TEST_CASE("scene budget: the key where a total passes its limit, with the numbers and the way to raise it") {
  const std::string head =
      "name: b\n"                                     // 1
      "particles:\n"                                  // 2
      "  - {name: p, pos: [0, 0]}\n"                  // 3
      "grids:\n"                                      // 4
      "  - name: g\n"                                 // 5
      "    size: [4, 3]\n"                            // 6
      "    springs: {structural: {ks: 1}}\n";         // 7
  SUBCASE("particles: a grid past the limit is refused at its size, before it is built") {
    SceneLimits limits;
    limits.particles = 12;  // 1 particle + 12 grid particles = 13
    const BudgetRefusal r = refusalOf(head, limits);
    CHECK(r.line == 6);
    CHECK(r.keyPath == "grids[0].size");
    CHECK(r.message ==
          "this makes 13 particles in the scene so far, more than the limit of 12 (counted before anything is "
          "built); if the scene is meant to be this large, raise the limit with --limit particles=N");
  }
  SUBCASE("springs: a grid's spring families") {
    SceneLimits limits;
    limits.springs = 16;  // structural on 4 × 3: 3·3 across + 2·4 down = 17
    const BudgetRefusal r = refusalOf(head, limits);
    CHECK(r.line == 7);
    CHECK(r.keyPath == "grids[0].springs");
    CHECK(r.message.find("this makes 17 springs, more than the limit of 16") == 0);
  }
  SUBCASE("springs: one point paired with a whole grid, then a row") {
    SceneLimits limits;
    limits.springs = 17 + 12 + 3;  // grid springs + p to each of g + p to each of row 0 = 33
    const BudgetRefusal r = refusalOf(head +
                                    "forces:\n"                                    // 8
                                    "  - {type: spring, a: p, b: g, ks: 1}\n"      // 9
                                    "  - {type: spring, a: p, b: 'g[0][*]', ks: 1}\n",  // 10
                                limits);
    CHECK(r.line == 10);
    CHECK(r.keyPath == "forces[1]");
    CHECK(r.message.find("this makes 33 springs and forces in the scene so far, more than the limit of 32") == 0);
  }
  SUBCASE("endpoints: a list of whole-grid references") {
    SceneLimits limits;
    limits.endpoints = 35;  // 3 × 12 = 36
    const BudgetRefusal r = refusalOf(head +
                                    "forces:\n"                                          // 8
                                    "  - {type: spring, a: [g, g, g], b: p, ks: 1}\n",  // 9
                                limits);
    CHECK(r.line == 9);
    CHECK(r.keyPath == "forces[0].a");
    CHECK(r.message.find("this makes 36 points named by references, more than the limit of 35") == 0);
    CHECK(r.message.find("--limit endpoints=N") != std::string::npos);
  }
  SUBCASE("constraints: a wire holding a column") {
    SceneLimits limits;
    limits.constraints = 2;
    const BudgetRefusal r = refusalOf(head +
                                    "constraints:\n"  // 8
                                    "  - {type: circular_wire, particles: 'g[*][0]', center: [0, 0]}\n",  // 9
                                limits);
    CHECK(r.line == 9);
    CHECK(r.keyPath == "constraints[0]");
    CHECK(r.message.find("this makes 3 constraints, more than the limit of 2") == 0);
  }
  SUBCASE("entries: one entry repeated through YAML aliases counts once per repetition") {
    SceneLimits limits;
    limits.entries = 3;
    const BudgetRefusal r = refusalOf(head +
                                    "forces:\n"                        // 8
                                    "  - &gravity {type: gravity}\n"  // 9
                                    "  - *gravity\n"                   // 10
                                    "  - *gravity\n"                   // 11
                                    "  - *gravity\n",                  // 12
                                limits);
    CHECK(r.line == 9);  // yaml-cpp gives an alias its anchor's node, and so its position
    CHECK(r.keyPath == "forces[3]");
    CHECK(r.message.find("this makes 4 entries in forces, constraints, colliders and mouse in the scene so far") == 0);
  }
}

TEST_CASE("scene budget: small files that expand to millions of springs are refused before the grid is built") {
  // 736 bytes: a 1000 × 1000 grid and a spring list of 200 whole-grid references
  // (200,000,000 endpoints). Here at the default limits.
  std::string refs;
  for (int i = 0; i < 200; ++i) refs += i ? ", g" : "g";
  const std::string grid = "name: big\ngrids:\n  - {name: g, size: [1000, 1000]}\n";
  const BudgetRefusal many = refusalOf(grid + "forces:\n  - {type: spring, a: [" + refs + "], b: [" + refs + "], ks: 1}\n",
                                 SceneLimits{});
  CHECK(many.keyPath == "forces[0].a");
  CHECK(many.message.find("this makes 200000000 points named by references") == 0);
  // One grid-to-point spring (999,000 springs) repeated through aliases.
  std::string aliases =
      "name: big\nparticles:\n  - {name: h, pos: [0, 1]}\ngrids:\n  - {name: g, size: [1000, 999]}\n"
      "forces:\n  - &s {type: spring, a: g, b: h, ks: 1}\n";
  for (int i = 0; i < 60; ++i) aliases += "  - *s\n";
  const BudgetRefusal repeated = refusalOf(aliases, SceneLimits{});
  CHECK(repeated.keyPath == "forces[8]");  // the ninth repetition passes the default of 8,000,000
  CHECK(repeated.message.find("this makes 8991000 springs and forces in the scene so far") == 0);
}

TEST_CASE("scene budget: --limit NAME=N") {
  SceneLimits limits;
  applyLimitOption(limits, "springs=20000000");
  CHECK(limits.springs == 20'000'000);
  applyLimitOption(limits, "particles=1");
  CHECK(limits.particles == 1);
  const std::pair<const char*, const char*> bad[] = {
      {"springs", "expected NAME=N with NAME one of particles, springs, constraints, endpoints, entries, nodes"},
      {"spring=5",
       "unknown limit 'spring'; expected one of particles, springs, constraints, endpoints, entries, "
       "nodes"},
      {"springs=0", "expected a whole number from 1 to 1000000000 after '=', got '0'"},
      {"springs=1e6", "expected a whole number from 1 to 1000000000 after '=', got '1e6'"},
      {"springs=99999999999999999999999",
       "expected a whole number from 1 to 1000000000 after '=', got "
       "'99999999999999999999999'"},
      {"springs=", "expected a whole number from 1 to 1000000000 after '=', got ''"},
  };
  for (const auto& [text, message] : bad) {
    CAPTURE(text);
    try {
      applyLimitOption(limits, text);
      FAIL("accepted");
    } catch (const ScenarioError& e) {
      CHECK(e.message() == message);
      CHECK(e.origin() == std::string("--limit ") + text);
    }
  }
}

TEST_CASE("scene budget: the YAML nodes of a file, counted before any is built") {
  // A map of 3 keys: the map, 3 keys, "a", a list, its map, its 2 keys, "p", a list and its 2 numbers.
  const std::string text = "name: a\nparticles:\n  - {name: p, pos: [0, 0]}\n";
  SceneLimits exact;
  exact.nodes = 12;
  CHECK_NOTHROW(loadScenarioText(text, "s.yaml", {}, exact));
  SceneLimits below;
  below.nodes = 11;
  CHECK_THROWS_WITH_AS(loadScenarioText(text, "s.yaml", {}, below), doctest::Contains("--limit nodes=N"),
                       ScenarioError);
  // A flow list longer than the limit is refused at its bracket, before yaml-cpp's scanner holds it.
  try {
    loadScenarioText("name: a\ndescription: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13]\n", "s.yaml", {}, below);
    FAIL("accepted");
  } catch (const ScenarioError& e) {
    CHECK(e.line() == 2);
    CHECK(e.column() == 14);
    CHECK(std::string(e.what()).find("more than 11 values, keys and lists") != std::string::npos);
  }
}
