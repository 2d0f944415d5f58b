// Golden manifests (src/scenario/golden_manifest.hpp): a full manifest read into its structs, and
// each mistake refused with the file, line, column and key path where it is written. The schema
// (`particles schema --golden`) is checked against the same files by tests/schema/ (CTest's
// schema:scenarios); here, that the loader agrees with it on them.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>
#include <string>

#include "render/render_options.hpp"
#include "scenario/golden_manifest.hpp"
#include "scenario/scenario_error.hpp"

using namespace particles::scenario;
namespace fs = std::filesystem;

namespace {

const fs::path kCheckout = PARTICLES_SOURCE_DIR;

GoldenManifest loadManifest(const std::string& yaml) {
  return loadGoldenManifestText(yaml, "golden.yaml", "dir");
}

struct ManifestError {
  int line = -1, column = -1;
  std::string keyPath, message, what;
};

ManifestError manifestErrorOf(const std::string& yaml) {
  try {
    loadManifest(yaml);
  } catch (const ScenarioError& e) {
    return {e.line(), e.column(), e.keyPath(), e.message(), e.what()};
  }
  FAIL("expected a ScenarioError for:\n" << yaml);
  return {};
}

void expectManifestError(const std::string& yaml, int line, int column, const std::string& keyPath,
                 const std::string& fragment) {
  const ManifestError r = manifestErrorOf(yaml);
  CAPTURE(yaml);
  CAPTURE(r.what);
  CHECK(r.line == line);
  CHECK(r.column == column);
  CHECK(r.keyPath == keyPath);
  CHECK(r.message.find(fragment) != std::string::npos);
  CHECK(r.what.rfind("golden.yaml", 0) == 0);  // the message starts with the file name
}

// One frame entry, so that the cases below can add what they test after it (line 2).
const std::string kOneFrame = "frames:\n  - {scenario: a.yaml, times: [1]}\n";

// A manifest with every key, each line numbered for the checks of the case that reads them all.
const std::string kEveryKeyManifest =
    "references: refs\n"                                                                    // 1
    "defaults:\n"                                                                           // 2
    "  render: {size: 320x240, msaa: 4, theme: dark, background: theme, raster: auto}\n"    // 3
    "  tolerance: {threshold: 16, max_share: 0.0002}\n"                                     // 4
    "  state_tolerance: {position: 1e-9, velocity: 2e-9, angle: 3e-9, omega: 4e-9}\n"       // 5
    "frames:\n"                                                                             // 6
    "  - scenario: ../scenarios/cloth.yaml\n"                                               // 7
    "    times: [10, 0.5, 2.5]\n"                                                           // 8
    "    set: {\"grids[0].springs.structural.ks\": [26.25, 1.05], simulation.dt: 0.001}\n"  // 9
    "    render: {raster: tiles, size: 640X360}\n"                                          // 10
    "    tolerance: {max_share: 0.0005}\n"                                                  // 11
    "  - scenario: /abs/soft_body.yaml\n"                                                   // 12
    "    times: [4.434]\n"                                                                  // 13
    "    name: \"{scenario}_control\"\n"                                                    // 14
    "    set: [\"simulation.dt=0.002\", \"forces[1].ks=[5, 6]\"]\n"                         // 15
    "    expect: differ\n"                                                                  // 16
    "states:\n"                                                                             // 17
    "  - scenario: ../scenarios/soft_body.yaml\n"                                           // 18
    "    times: [37.5, 9]\n"                                                                // 19
    "    state_tolerance: {position: 1e-6}\n"                                               // 20
    "  - {scenario: rigid_chain.yaml, times: [1], name: \"chain+{scenario}\"}\n";           // 21

}  // namespace

TEST_CASE("golden manifest: every key read into its structs, paths resolved, times sorted, names expanded") {
  const GoldenManifest m = loadManifest(kEveryKeyManifest);
  CHECK(m.file == "golden.yaml");
  CHECK(m.references == fs::path("dir/refs"));

  REQUIRE(m.defaultRender.size);
  CHECK(m.defaultRender.size->value == std::pair(320, 240));
  CHECK(m.defaultRender.size->at.line == 3);
  CHECK(m.defaultRender.size->at.column == 18);
  CHECK(m.defaultRender.size->at.keyPath == "defaults.render.size");
  REQUIRE(m.defaultRender.msaa);
  CHECK(m.defaultRender.msaa->value == 4);
  CHECK(m.defaultRender.theme->value == "dark");
  CHECK(m.defaultRender.background->value == "theme");
  CHECK(m.defaultRender.raster->value == "auto");
  CHECK(m.defaultRender.raster->at.keyPath == "defaults.render.raster");
  CHECK(m.defaultTolerance.threshold->value == 16);
  CHECK(m.defaultTolerance.maxShare->value == 0.0002);
  CHECK(m.defaultStateTolerance.position->value == 1e-9);
  CHECK(m.defaultStateTolerance.velocity->value == 2e-9);
  CHECK(m.defaultStateTolerance.angle->value == 3e-9);
  CHECK(m.defaultStateTolerance.omega->value == 4e-9);
  CHECK(m.defaultStateTolerance.omega->at.line == 5);

  REQUIRE(m.frames.size() == 2);
  const GoldenEntry& cloth = m.frames[0];
  CHECK(cloth.scenarioGiven == "../scenarios/cloth.yaml");
  CHECK(cloth.scenario == fs::path("dir/../scenarios/cloth.yaml"));
  CHECK(cloth.scenarioAt.line == 7);
  CHECK(cloth.scenarioAt.column == 15);
  CHECK(cloth.scenarioAt.keyPath == "frames[0].scenario");
  CHECK(cloth.at.line == 7);
  CHECK(cloth.at.column == 5);
  CHECK(cloth.at.keyPath == "frames[0]");
  REQUIRE(cloth.times.size() == 3);
  const std::vector<std::tuple<double, std::string, std::string, int, std::string>> times = {
      {0.5, "0.5", "cloth_t0.5", 17, "frames[0].times[1]"},
      {2.5, "2.5", "cloth_t2.5", 22, "frames[0].times[2]"},
      {10.0, "10", "cloth_t10", 13, "frames[0].times[0]"}};
  for (size_t i = 0; i < times.size(); ++i) {
    CAPTURE(i);
    const auto& [seconds, text, frameName, column, keyPath] = times[i];
    CHECK(cloth.times[i].seconds == seconds);
    CHECK(cloth.times[i].text == text);
    CHECK(cloth.times[i].frameName == frameName);
    CHECK(cloth.times[i].at.line == 8);
    CHECK(cloth.times[i].at.column == column);
    CHECK(cloth.times[i].at.keyPath == keyPath);
  }
  const std::vector<std::pair<std::string, std::string>> clothSets = {
      {"grids[0].springs.structural.ks", "[26.25, 1.05]"}, {"simulation.dt", "0.001"}};
  CHECK(cloth.sets == clothSets);
  REQUIRE(cloth.setsAt.size() == 2);
  CHECK(cloth.setsAt[0].line == 9);
  CHECK(cloth.setsAt[0].column == 45);
  CHECK(cloth.setsAt[0].keyPath == "frames[0].set.grids[0].springs.structural.ks");
  CHECK(cloth.setsAt[1].column == 75);
  CHECK(cloth.render.raster->value == "tiles");
  CHECK(cloth.render.size->value == std::pair(640, 360));
  CHECK(!cloth.render.msaa);  // not laid over the defaults here
  CHECK(!cloth.tolerance.threshold);
  CHECK(cloth.tolerance.maxShare->value == 0.0005);
  CHECK(!cloth.expectDiffer);
  CHECK(cloth.stateName.empty());

  const GoldenEntry& control = m.frames[1];
  CHECK(control.scenario == fs::path("/abs/soft_body.yaml"));
  REQUIRE(control.times.size() == 1);
  CHECK(control.times[0].text == "4.434");
  CHECK(control.times[0].frameName == "soft_body_control");
  CHECK(control.nameAt.line == 14);
  CHECK(control.nameAt.column == 11);
  CHECK(control.nameAt.keyPath == "frames[1].name");
  const std::vector<std::pair<std::string, std::string>> controlSets = {{"simulation.dt", "0.002"},
                                                                        {"forces[1].ks", "[5, 6]"}};
  CHECK(control.sets == controlSets);
  CHECK(control.setsAt[1].line == 15);
  CHECK(control.setsAt[1].column == 34);
  CHECK(control.setsAt[1].keyPath == "frames[1].set[1]");
  CHECK(control.expectDiffer);

  REQUIRE(m.states.size() == 2);
  const GoldenEntry& soft = m.states[0];
  CHECK(soft.stateName == "soft_body");
  CHECK(soft.times.size() == 2);
  CHECK(soft.times[0].text == "9");
  CHECK(soft.times[1].text == "37.5");
  CHECK(soft.times[0].frameName.empty());
  CHECK(soft.stateTolerance.position->value == 1e-6);
  CHECK(!soft.stateTolerance.velocity);
  CHECK(m.states[1].stateName == "chain+rigid_chain");
}

TEST_CASE("golden manifest: what may be left out") {
  // No references (the manifest's folder), no defaults, no frames.
  const GoldenManifest m = loadManifest("states:\n  - {scenario: sub/x.yaml, times: [0]}\n");
  CHECK(m.references == fs::path("dir"));
  CHECK(!m.defaultRender.size);
  CHECK(!m.defaultTolerance.threshold);
  CHECK(m.frames.empty());
  REQUIRE(m.states.size() == 1);
  CHECK(m.states[0].scenario == fs::path("dir/sub/x.yaml"));
  CHECK(m.states[0].stateName == "x");
  CHECK(m.states[0].nameAt.line == 2);  // not written: the entry's position
  // An empty list beside a full one, a name without {time} for one time, a time of 0 written "-0".
  const GoldenManifest n = loadManifest("states: []\nframes:\n  - {scenario: a.yaml, times: [-0], name: only}\n");
  REQUIRE(n.frames.size() == 1);
  CHECK(n.frames[0].times[0].frameName == "only");
  CHECK(n.frames[0].times[0].seconds == 0.0);
}

TEST_CASE("golden manifest: the sample counts are the renderer's") {
  CHECK(std::equal(std::begin(kGoldenSampleCounts), std::end(kGoldenSampleCounts),
                   particles::render::kSampleCounts.begin(), particles::render::kSampleCounts.end()));
  for (int n = 0; n <= 17; ++n) {
    CAPTURE(n);
    const std::string yaml = kOneFrame + "defaults: {render: {msaa: " + std::to_string(n) + "}}\n";
    const bool sampleCount =
        std::find(std::begin(kGoldenSampleCounts), std::end(kGoldenSampleCounts), n) != std::end(kGoldenSampleCounts);
    if (sampleCount) {
      CHECK(loadManifest(yaml).defaultRender.msaa->value == n);
    } else {
      CHECK_THROWS_AS(loadManifest(yaml), ScenarioError);
    }
  }
}

TEST_CASE("golden manifest: mistakes are refused where they are written") {
  SUBCASE("an unknown key, with the closest one") {
    expectManifestError("frames:\n  - scenario: a.yaml\n    times: [1]\n    tolerence: {threshold: 3}\n", 4, 5,
                "frames[0].tolerence", "unknown key 'tolerence'; did you mean 'tolerance'?");
    expectManifestError("frame:\n  - {scenario: a.yaml, times: [1]}\n", 1, 1, "frame", "did you mean 'frames'?");
  }
  SUBCASE("a state entry with render settings") {
    expectManifestError("states:\n  - {scenario: a.yaml, times: [1], render: {msaa: 4}}\n", 2, 36, "states[0].render",
                "unknown key 'render'");
  }
  SUBCASE("times: negative, repeated, not numbers, missing, empty") {
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1, -2]}\n", 2, 35, "frames[0].times[1]",
                "expected a number ≥ 0, got -2");
    expectManifestError("frames:\n  - scenario: a.yaml\n    times: [2.5, 1, 2.50]\n", 3, 21, "frames[0].times[2]",
                "the time 2.50 is listed twice (first as 2.5 at line 3)");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1, \"2\"]}\n", 2, 35, "frames[0].times[1]",
                "expected a number, got '2'");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [.inf]}\n", 2, 32, "frames[0].times[0]", "a finite number");
    expectManifestError("frames:\n  - {scenario: a.yaml}\n", 2, 5, "frames[0].times", "missing required key 'times'");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: []}\n", 2, 31, "frames[0].times", "an empty list");
  }
  SUBCASE("render settings out of range") {
    expectManifestError(kOneFrame + "defaults:\n  render: {size: 320by240}\n", 4, 18, "defaults.render.size",
                "expected a size WIDTHxHEIGHT in px, such as 320x240, got '320by240'");
    expectManifestError(kOneFrame + "defaults:\n  render: {size: 0x240}\n", 4, 18, "defaults.render.size",
                "expected each side of the size from 1 to 16384 px, got '0x240'");
    expectManifestError(kOneFrame + "defaults:\n  render: {size: 320x99999999999999999999999}\n", 4, 18, "defaults.render.size",
                "from 1 to 16384 px");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], render: {msaa: 3}}\n", 2, 51, "frames[0].render.msaa",
                "expected 1, 2, 4, 8, 16 samples per pixel (1: off), got 3");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], render: {theme: \"\"}}\n", 2, 52, "frames[0].render.theme",
                "expected a text");
  }
  SUBCASE("tolerances out of range") {
    expectManifestError(kOneFrame + "defaults:\n  tolerance: {threshold: 300}\n", 4, 26, "defaults.tolerance.threshold",
                "expected a whole number from 0 to 255, got 300");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], tolerance: {max_share: 2}}\n", 2, 59,
                "frames[0].tolerance.max_share", "expected a number from 0 to 1, got 2");
    expectManifestError(kOneFrame + "defaults:\n  state_tolerance: {omega: -1e-9}\n", 4, 28, "defaults.state_tolerance.omega",
                "expected a number ≥ 0");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], expect: same}\n", 2, 44, "frames[0].expect",
                "expected match or differ, got 'same'");
  }
  SUBCASE("sets that --set would not take") {
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], set: [dt]}\n", 2, 42, "frames[0].set[0]",
                "expected PATH=VALUE");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], set: {\"forces[1\": 2}}\n", 2, 42,
                "frames[0].set.forces[1", "cannot use this key path: unclosed '['");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], set: {simulation.dt: ~}}\n", 2, 42,
                        "frames[0].set.simulation.dt", "expected a value for --set");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], set: [a=1, a=2]}\n", 2, 47, "frames[0].set[1]",
                "'a' is set twice");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], set: [a=]}\n", 2, 42, "frames[0].set[0]",
                "expected a value for 'a'");
  }
}

TEST_CASE("golden manifest: names are file names, one per check, across frames and states") {
  SUBCASE("two checks of one name: at the later one in the file, naming the first") {
    const std::string shared =
        "frames:\n  - {scenario: cloth.yaml, times: [1], name: shared}\n"
        "states:\n  - {scenario: soft.yaml, times: [1], name: shared}\n";
    expectManifestError(shared, 4, 45, "states[0].name",
                "a second check named 'shared' (the first is frames[0].name at line 2)");
    const std::string statesFirst =
        "states:\n  - {scenario: soft.yaml, times: [1], name: shared}\n"
        "frames:\n  - {scenario: cloth.yaml, times: [1], name: shared}\n";
    expectManifestError(statesFirst, 4, 46, "frames[0].name", "(the first is states[0].name at line 2)");
    // Default names: the same scenario at the same time, reported at the time.
    const std::string twice =
        "frames:\n  - {scenario: cloth.yaml, times: [1, 2]}\n  - {scenario: x/cloth.yaml, times: [3, 2]}\n";
    expectManifestError(twice, 3, 41, "frames[1].times[1]", "a second check named 'cloth_t2' (the first is frames[0].times[1]");
  }
  SUBCASE("a frames name without {time} for more than one time") {
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1, 2], name: still}\n", 2, 45, "frames[0].name",
                "the name 'still' has no {time}, so the entry's 2 frames would share it: add {time} to the name");
  }
  SUBCASE("placeholders") {
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], name: \"{scenario}_{step}\"}\n", 2, 42, "frames[0].name",
                "unknown placeholder '{step}' in the name (known: {scenario}, {time})");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], name: \"{scenario\"}\n", 2, 42, "frames[0].name",
                "opens a '{' it does not close");
    expectManifestError("states:\n  - {scenario: a.yaml, times: [1], name: \"{scenario}_t{time}\"}\n", 2, 42, "states[0].name",
                "a state's name cannot hold {time}");
  }
  SUBCASE("characters, a leading dot, emptiness and length: at what makes them") {
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], name: \"cloth frame\"}\n", 2, 42, "frames[0].name",
                "the name 'cloth frame' is not a file name: only letters, digits and . _ + - may be in one");
    expectManifestError("frames:\n  - {scenario: a/b.yaml, times: [1], name: \"x/{time}\"}\n", 2, 44, "frames[0].name",
                "only letters, digits");
    expectManifestError("frames:\n  - {scenario: \"my cloth.yaml\", times: [1]}\n", 2, 16, "frames[0].scenario",
                "the name 'my cloth_t1' is not a file name: only letters, digits and . _ + - may be in one; give the "
                "entry a name");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [.5], name: \"{time}\"}\n", 2, 32, "frames[0].times[0]",
                "the name '.5' is not a file name: it starts with a dot; write the time another way");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], name: \".{scenario}\"}\n", 2, 42, "frames[0].name",
                "it starts with a dot");
    expectManifestError("states:\n  - {scenario: sub/, times: [1]}\n", 2, 16, "states[0].scenario", "it is empty");
    const std::string longName(kMaxGoldenNameLength, 'n');
    CHECK(loadManifest("frames:\n  - {scenario: a.yaml, times: [1], name: " + longName + "}\n").frames[0].times[0].frameName ==
          longName);
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1], name: " + longName + "x}\n", 2, 42, "frames[0].name",
                "it is longer than 200 characters");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [1" + std::string(200, '0') + "], name: \"t{time}\"}\n", 2, 32,
                "frames[0].times[0]", "it is longer than 200 characters");
  }
}

TEST_CASE("golden manifest: the file as a whole") {
  SUBCASE("empty") {
    expectManifestError("", 1, 1, "", "the file is empty; expected a golden manifest (frames: and/or states:)");
    expectManifestError("# nothing yet\n", 1, 1, "", "the file is empty");
  }
  SUBCASE("nothing to check") {
    expectManifestError("frames: []\nstates: []\n", 1, 1, "", "a manifest with nothing to check");
    expectManifestError("references: refs\n", 1, 1, "", "a manifest with nothing to check");
  }
  SUBCASE("two documents") {
    expectManifestError(kOneFrame + "---\nstates: []\n", 4, 1, "", "more than one YAML document; expected one golden manifest");
  }
  SUBCASE("a stray comma") {
    expectManifestError(",\n", 1, 1, "", "YAML syntax error");
  }
  SUBCASE("an alias") {
    expectManifestError(
        "defaults:\n  tolerance: &t {threshold: 3}\nframes:\n  - {scenario: a.yaml, times: [1], tolerance: *t}\n", 4,
        47, "", "an alias (*name)");
  }
  SUBCASE("not a map") {
    expectManifestError("- 1\n", 1, 1, "", "expected a map of keys, got a list of 1");
  }
  SUBCASE("more checks than a manifest may make, refused before the rest is read") {
    std::string times;
    for (int i = 0; i < 60'000; ++i) {
      // Not `(i ? "," : "") + std::to_string(i)`: GCC 12 at -O3 sees a memcpy overlap there
      // (-Wrestrict, a false positive: GCC bug 105329).
      if (i > 0) times += ',';
      times += std::to_string(i);
    }
    const std::string yaml =
        "frames:\n  - {scenario: a.yaml, times: [" + times + "]}\n  - {scenario: b.yaml, times: [" + times + "]}\n";
    expectManifestError(yaml, 3, 5, "frames[1]", "more than 100000 checks");
    expectManifestError("frames:\n  - {scenario: a.yaml, times: [" + times + "," + times + "]}\n", 2, 31, "",
                "a list of more than 100000 items");
  }
}

TEST_CASE("golden manifest: a file, its folder, and the schema's good and bad examples") {
  const fs::path dir = fs::temp_directory_path() / "particles_golden_manifest_test";
  fs::create_directories(dir);
  std::ofstream(dir / "m.yaml") << "frames:\n  - {scenario: c.yaml, times: [1]}\n";
  const GoldenManifest m = loadGoldenManifestFile(dir / "m.yaml", 1);
  CHECK(m.file == (dir / "m.yaml").string());
  CHECK(m.references == dir);
  CHECK(m.frames[0].scenario == dir / "c.yaml");
  try {
    loadGoldenManifestFile(dir / "missing.yaml", 1);
    FAIL("a missing file loaded");
  } catch (const ScenarioError& e) {
    CHECK(e.file() == (dir / "missing.yaml").string());
    CHECK(e.message().find("cannot open") != std::string::npos);
  }
  fs::remove_all(dir);

  // tests/schema/golden: the files the schema takes loadManifest, those it refuses do not (schema:scenarios
  // checks the schema's side with python3-jsonschema).
  const fs::path examples = kCheckout / "tests/schema/golden";
  int good = 0, bad = 0;
  for (const auto& e : fs::directory_iterator(examples)) {
    if (e.path().extension() != ".yaml") continue;
    CAPTURE(e.path());
    CHECK_NOTHROW(loadGoldenManifestFile(e.path(), 1));
    ++good;
  }
  for (const auto& e : fs::directory_iterator(examples / "bad")) {
    CAPTURE(e.path());
    CHECK_THROWS_AS(loadGoldenManifestFile(e.path(), 1), ScenarioError);
    ++bad;
  }
  CHECK(good >= 2);
  CHECK(bad >= 10);
}

TEST_CASE("golden manifest: the JSON Schema") {
  const std::string text = goldenManifestJsonSchema();
  CHECK(text.back() == '\n');
  const nlohmann::json schema = nlohmann::json::parse(text);
  CHECK(schema["$schema"] == "http://json-schema.org/draft-07/schema#");
  CHECK(schema["additionalProperties"] == false);
  const nlohmann::json frame = schema["properties"]["frames"]["anyOf"][0]["items"];
  CHECK(frame["required"] == nlohmann::json::array({"scenario", "times"}));
  CHECK(frame["additionalProperties"] == false);
  CHECK(frame["properties"]["expect"]["anyOf"][0]["enum"] == nlohmann::json::array({"match", "differ"}));
  const nlohmann::json render = frame["properties"]["render"]["anyOf"][0];
  CHECK(render["properties"]["msaa"]["anyOf"][0]["enum"] == nlohmann::json::array({1, 2, 4, 8, 16}));
  const nlohmann::json state = schema["properties"]["states"]["anyOf"][0]["items"];
  CHECK(!state["properties"].contains("render"));
  CHECK(state["properties"].contains("state_tolerance"));
}

TEST_CASE("golden manifest: a map of sets passes text as the file wrote it, and maps whole") {
  const GoldenManifest m = loadManifest(
      "frames:\n"
      "  - scenario: a.yaml\n"
      "    times: [1]\n"
      "    set: {style.title: \"Pendulum: RK4\", style.particles.color: \"#ff0000\", style.colorbar: {for: particles},"
      " integrator: \"rk4\", style.label: 'it''s'}\n");
  REQUIRE(m.frames.size() == 1);
  const auto& sets = m.frames[0].sets;
  REQUIRE(sets.size() == 5);
  // Each value as --set takes it: YAML that reads back as what the manifest wrote.
  CHECK(sets[0].second == "\"Pendulum: RK4\"");
  CHECK(sets[1].second == "\"#ff0000\"");
  CHECK(sets[2].second == "{for: particles}");
  CHECK(sets[3].second == "rk4");  // plain text reads back the same: no quotes needed
  CHECK(sets[4].second == "it's");
  for (const auto& [path, value] : sets) {
    INFO(path);
    const YAML::Node back = YAML::Load(value);
    if (back.IsScalar()) CHECK(back.Scalar() != "");
  }
  CHECK(YAML::Load(sets[0].second).Scalar() == "Pendulum: RK4");
  CHECK(YAML::Load(sets[1].second).Scalar() == "#ff0000");
}
