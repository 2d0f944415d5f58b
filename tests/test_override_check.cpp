// OverrideChecker (scenario/override_check.hpp): a scenario parsed and loaded once, then checked
// against many overrides, each reading only the part of the file it changes. Whatever it reads, its
// outcome must be loadScenarioText's with the same overrides: the same error, byte for byte (file,
// line, key path, the option the value came from, the bound), or the same settings. Each case below
// is compared with a whole load, on the repository's scenarios, alone and in combinations whose
// parts interact, twice (the second time from what the checker remembers), and after errors.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "scenario/override_check.hpp"
#include "scenario/scenario.hpp"
#include "source_tree.hpp"

using namespace particles::scenario;

using particles::test::kSource;

namespace {


std::string scenarioText(const std::string& name) {
  std::ifstream in(kSource + "/scenarios/" + name);
  std::ostringstream text;
  text << in.rdbuf();
  REQUIRE_MESSAGE(!text.str().empty(), name);
  return text.str();
}

std::string describe(const ScenarioSettings& s) {
  return fmt::format("{} dt {} duration {} solver {} | {}x{} fps {} view [{}, {}] {}",
                     integratorName(s.simulation.integrator), s.simulation.dt, s.simulation.duration,
                     implicitSolverName(s.simulation.implicitSolver), s.render.width, s.render.height, s.render.fps,
                     s.render.viewCenter.x(), s.render.viewCenter.y(), s.render.viewHeight);
}

// The settings a load gives, or its error's whole text.
template <class Load>
std::string outcome(const Load& load) {
  try {
    return describe(load());
  } catch (const ScenarioError& e) {
    return std::string("error: ") + e.what();
  }
}

// `path=value` pairs as overrides, each with an origin of its own as a sweep gives them.
std::vector<Override> overrides(const std::vector<std::pair<std::string, std::string>>& pairs) {
  std::vector<Override> out;
  for (const auto& [path, value] : pairs) out.push_back({path, value, fmt::format("the sweep's {}={}", path, value)});
  return out;
}

std::string wholeLoad(const std::string& text, const std::string& file, const std::vector<Override>& fixed,
                      const std::vector<Override>& changes) {
  std::vector<Override> all = fixed;
  all.insert(all.end(), changes.begin(), changes.end());
  return outcome([&] {
    const Scenario s = loadScenarioText(text, file, all);
    return ScenarioSettings{s.simulation, s.render};
  });
}

using OverrideCase = std::vector<std::pair<std::string, std::string>>;

void expectSameAsWholeLoads(const std::string& name, const std::vector<OverrideCase>& cases,
                            const std::vector<Override>& fixed = {}) {
  const std::string text = scenarioText(name);
  OverrideChecker checker(text, name, fixed);
  for (int round = 0; round < 2; ++round) {
    for (const OverrideCase& c : cases) {
      const std::vector<Override> changes = overrides(c);
      CAPTURE(name);
      CAPTURE(round);
      std::string shown;
      for (const auto& [path, value] : c) shown += path + "=" + value + "; ";
      CAPTURE(shown);
      const std::string expected = wholeLoad(text, name, fixed, changes);
      CHECK(outcome([&] { return checker.check(changes); }) == expected);
    }
  }
  // Every override taken back: the scenario as it was.
  CHECK(outcome([&] { return checker.check({}); }) == wholeLoad(text, name, fixed, {}));
}

}  // namespace

TEST_CASE("OverrideChecker: a kind entry's keys, the settings, a grid's springs and mass, as a whole load") {
  expectSameAsWholeLoads(
      "cloth.yaml",
      {
          {{"forces[1].kd", "0.5"}},
          {{"forces[1].kd", "-2"}},
          {{"forces[1].kss", "1"}},  // an unknown key, added to the entry
          {{"forces[9].ks", "1"}},   // no such entry: a whole load
          {{"forces.1.kd", "3"}},
          {{"forces[1].kd", "{a: 1}"}},
          {{"forces[1].kd", ""}},
          {{"forces[1].kd", "[1"}},
          {{"forces[1].kd.x", "1"}},
          {{"forces[1].type", "gravityx"}},
          {{"forces[1]", "3"}},
          {{"forces[0].g", "[0]"}},
          {{"forces[0].g", "[0, -1.5]"}},
          {{"mouse[0].to", "1"}},    // before the file's 'from'
          {{"mouse[0].from", "5"}},  // after the file's 'to': the error is at 'to', on its line of the file
          {{"mouse[0].path", "[[0]]"}},
          {{"mouse[0].grab", "cloth[30][0]"}},  // a reference: a whole load
          {{"constraints[0].y", "abc"}},
          {{"constraints[0].particles", "nobody"}},
          {{"simulation.dt", "1e-12"}},
          {{"simulation.integrator", "rk5"}},
          {{"simulation", "3"}},
          {{"simulation", "{dt: 0.5, duration: 2}"}},
          {{"simulation.implicit_solver", "direct"}},
          {{"render.fps", "0"}},
          {{"render.fps", "24"}},
          {{"render.view", "5"}},
          {{"render.view.height", "-1"}},
          {{"render.size", "[640, 480]"}},
          {{"grids[0].springs.structural.ks", "[1, 2, 3]"}},
          {{"grids[0].springs.structural.ks", "[12.5, 0.5]"}},
          {{"grids[0].springs.structural.kss", "1"}},
          {{"grids[0].springs.structural", "5"}},
          {{"grids[0].springs.shear.ks", "-1"}},  // a family the file does not have: a whole load
          {{"grids[0].size", "[0, 1]"}},
          {{"grids[0].size", "[5, 5]"}},  // the mouse's grab is then out of the grid
          {{"grids[0].mass", "0"}},
          {{"grids[0].mass", "\"1\""}},
          {{"name", "other"}},
          {{"description", "[1]"}},
          // Several at once, in one part and in several: the first error is the whole load's.
          {{"mouse[0].from", "5"}, {"mouse[0].to", "6"}},
          {{"mouse[0].from", "5"}, {"mouse[0].to", "4"}},
          {{"simulation.dt", "0.001"}, {"simulation.duration", "1e7"}},
          {{"forces[1].kd", "-1"}, {"grids[0].mass", "0"}},
          {{"forces[1].kd", "-1"}, {"simulation.dt", "abc"}},
          {{"forces[1].kd", "1"}, {"forces[0].g", "[1"}},
          {{"render.view", "5"}, {"render.view.height", "2"}},  // the first changes the second's way
          {{"render.view", "{center: [0, 0]}"}, {"render.view.height", "2"}},
          {{"render.view.height", "2"}, {"render.view", "{center: [1, 1]}"}},
          {{"forces[1].kd", "0.1"}, {"forces[1].kd", "-0.1"}},
          {{"grids[0].size", "[0, 1]"}, {"forces[1].kd", "[1"}},
          {{"grids[0].mass", "0.01"}, {"forces[1].kd", "0.1"}, {"mouse[0].ks", "3"}, {"render.fps", "30"}},
      });
}

TEST_CASE("OverrideChecker: particles, rigid bodies, positions and references, as a whole load") {
  expectSameAsWholeLoads("springs.yaml", {
                                             {{"particles[3].mass", "-1"}},
                                             {{"particles[3].mass", "2"}},
                                             {{"particles[3].vel", "[1]"}},
                                             {{"particles[3].vel", "[1, 2]"}},
                                             {{"particles[3].pos", "[x, 1]"}},
                                             {{"particles[3].name", "hook_a"}},  // taken: a whole load
                                             {{"particles[3].fixed", "maybe"}},
                                             {{"rigid_bodies[0].omega", "abc"}},
                                             {{"rigid_bodies[0].mass", "0"}},
                                             {{"rigid_bodies[0].vel", "[0, 1]"}},
                                             {{"rigid_bodies[0].angle", "1"}},
                                             {{"forces[1].a", "nobody"}},
                                             {{"forces[1].b", "hook_a"}},  // a spring from hook_a to itself
                                             {{"forces[1].rest", "-1"}},
                                             {{"forces[1].ks", "[0]"}},
                                             {{"forces[1].ks[0]", "1"}},
                                             {{"forces[4].kd", "-1"}, {"particles[7].mass", "0"}},
                                         });
  expectSameAsWholeLoads("rod_pendulum.yaml", {
                                                  {{"particles[1].pos", "[0, 0.5]"}},  // the rod's ends coincide
                                                  {{"constraints[0].length", "0"}},
                                                  {{"constraints[0].length", "2"}},
                                              });
  expectSameAsWholeLoads("bead_on_wire.yaml", {
                                                  {{"constraints[0].center", "[-1.6, 0]"}},
                                                  {{"constraints[0].radius", "-1"}},
                                                  {{"particles[0].pos", "[-1, 0]"}},
                                              });
}

TEST_CASE("OverrideChecker: a file with aliases, and fixed overrides first") {
  // soft_body.yaml's grids share one springs map by an alias: an override of one grid's springs
  // changes them all, and a whole load names the first grid that reads it.
  expectSameAsWholeLoads("soft_body.yaml", {
                                               {{"grids[1].springs.shear.kd", "-1"}},
                                               {{"grids[0].springs.structural.ks", "3"}},
                                               {{"forces[1].ks", "-3"}},
                                           });
  const std::vector<Override> fixed = {{"simulation.duration", "2", "the sweep's options.duration"},
                                       {"forces[1].kd", "0.5", "the sweep's options.set"}};
  expectSameAsWholeLoads("cloth.yaml",
                         {
                             {{"simulation.dt", "1e-9"}},  // 2 s of it: more steps than allowed
                             {{"simulation.dt", "0.05"}},
                             {{"forces[1].kd", "-1"}},
                             {{"forces[1].ks", "1"}},  // beside the fixed kd
                         },
                         fixed);
}

TEST_CASE("OverrideChecker::checkTogether: a job's overrides of one part together, the settings under all") {
  const std::string text = scenarioText("cloth.yaml");
  OverrideChecker checker(text, "cloth.yaml", {});
  // Each alone loads (the file has from 1.5, to 3.5); together they do not: 'to' before 'from'.
  const auto from = overrides({{"mouse[0].from", "3"}}), to = overrides({{"mouse[0].to", "2"}});
  CHECK_NOTHROW(checker.check(from));
  CHECK_NOTHROW(checker.check(to));
  const auto both = overrides({{"mouse[0].from", "3"}, {"mouse[0].to", "2"}});
  CHECK_THROWS_AS(checker.checkTogether(both), ScenarioError);
  CHECK(outcome([&] { return checker.checkTogether(both); }) == wholeLoad(text, "cloth.yaml", {}, both));
  // An override that changes what other parts read is left out (it was checked alone) ...
  const auto grid = overrides({{"grids[0].size", "[5, 5]"}, {"simulation.duration", "3"}, {"render.fps", "24"}});
  const ScenarioSettings s = checker.checkTogether(grid);
  // ... and the settings are those the job loads with.
  CHECK(s.simulation.duration == 3);
  CHECK(s.render.fps == 24);
  CHECK(s.simulation.dt == 0.01);
}

TEST_CASE("OverrideChecker: a scenario without a simulation section, its settings under a job's overrides") {
  const std::string text =
      "name: bare\nparticles:\n  - {name: a, pos: [0, 0]}\n  - {name: b, pos: [1, 0]}\n"
      "forces:\n  - {type: spring, a: a, b: b, ks: 1}\n";
  OverrideChecker checker(text, "bare.yaml", {});
  // simulation.dt creates the section: no part of the file to read alone, so a whole load.
  const auto job = overrides({{"simulation.dt", "0.5"}, {"forces[0].ks", "2"}});
  CHECK(outcome([&] { return checker.check(job); }) == wholeLoad(text, "bare.yaml", {}, job));
  CHECK(checker.checkTogether(job).simulation.dt == 0.5);
  const auto bad = overrides({{"simulation.dt", "-1"}});
  CHECK(outcome([&] { return checker.check(bad); }) == wholeLoad(text, "bare.yaml", {}, bad));
}
