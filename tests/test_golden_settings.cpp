// What a golden check runs with, before anything is simulated: which checks a manifest and the
// options select (golden::selectChecks), which setting wins (an entry's own, over the run's
// command line, over the manifest's defaults, over the programs' defaults), the look options'
// two-way mapping (render::lookOptions) and the exact commands that reproduce a result.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "golden/check.hpp"
#include "golden/check_settings.hpp"
#include "golden/reproduce_commands.hpp"
#include "render/image_compare.hpp"
#include "render/render_options.hpp"
#include "scenario/golden_manifest.hpp"
#include "scenario/scenario_error.hpp"

namespace fs = std::filesystem;
using namespace particles;
using test::Scratch;
using golden::CheckOptions;
using golden::CheckOverrides;
using scenario::GoldenCheck;
using scenario::GoldenManifest;

namespace {

GoldenManifest load(const std::string& yaml, const fs::path& directory = "dir") {
  return scenario::loadGoldenManifestText(yaml, "golden.yaml", directory);
}

std::vector<std::string> namesOf(const std::vector<GoldenCheck>& checks) {
  std::vector<std::string> names;
  for (const GoldenCheck& c : checks) names.push_back(c.name);
  return names;
}

// Two frame entries (three frames) and two states.
const std::string kFourEntries =
    "frames:\n"
    "  - {scenario: a.yaml, times: [1, 2]}\n"
    "  - {scenario: b.yaml, times: [3], reference: a_t1}\n"
    "states:\n"
    "  - {scenario: c.yaml, times: [1]}\n"
    "  - {scenario: d.yaml, times: [1]}\n";

}  // namespace

TEST_CASE("golden checks: a manifest's checks are its frames, time by time, then its states") {
  const GoldenManifest m = load(kFourEntries);
  const std::vector<GoldenCheck> checks = scenario::goldenChecks(m);
  REQUIRE(checks.size() == 5);
  CHECK(namesOf(checks) == std::vector<std::string>{"a_t1", "a_t2", "b_t3", "c", "d"});
  CHECK(checks[1].kind == GoldenCheck::Kind::frame);
  CHECK(checks[1].entry == 0);
  CHECK(checks[1].time == 1);
  CHECK(checks[2].entry == 1);
  CHECK(checks[2].time == 0);
  CHECK(checks[4].kind == GoldenCheck::Kind::state);
  CHECK(checks[4].entry == 1);
  CHECK(golden::checkNames(m) == namesOf(checks));
}

TEST_CASE("golden checks: --only, --missing and --shard select in manifest order") {
  Scratch temp;
  const GoldenManifest m = load(kFourEntries, temp.dir);
  CheckOptions o;
  CHECK(namesOf(golden::selectChecks(m, o)) == std::vector<std::string>{"a_t1", "a_t2", "b_t3", "c", "d"});

  o.only = {"d", "a_t2"};  // in manifest order, whatever the order given
  CHECK(namesOf(golden::selectChecks(m, o)) == std::vector<std::string>{"a_t2", "d"});
  o.only = {"a_t3"};
  try {
    golden::selectChecks(m, o);
    FAIL("an --only name the manifest lacks was taken");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()) == "no frame or state of the manifest is named 'a_t3'; did you mean a_t1?");
  }
  o.only.clear();

  // --missing: the references that do not exist; never b_t3, which compares with a_t1's.
  o.missingOnly = true;
  CHECK(namesOf(golden::selectChecks(m, o)) == std::vector<std::string>{"a_t1", "a_t2", "c", "d"});
  std::ofstream(temp.dir / "a_t1.png") << "x";
  std::ofstream(temp.dir / "c.csv") << "x";
  fs::create_symlink("nowhere", temp.dir / "d.csv");  // a broken link is there: not missing
  CHECK(namesOf(golden::selectChecks(m, o)) == std::vector<std::string>{"a_t2"});
  o.missingOnly = false;

  // --shard K/N: contiguous blocks of total·(K−1)/N … total·K/N.
  const std::vector<std::vector<std::string>> shards = {{"a_t1"}, {"a_t2", "b_t3"}, {"c", "d"}};
  for (int k = 1; k <= 3; ++k) {
    CAPTURE(k);
    o.shard = {k, 3};
    CHECK(namesOf(golden::selectChecks(m, o)) == shards[size_t(k - 1)]);
  }
  o.only = {"a_t1", "c", "d"};  // the shard cuts what the other options selected
  o.shard = {2, 2};
  CHECK(namesOf(golden::selectChecks(m, o)) == std::vector<std::string>{"c", "d"});
  for (const auto& [k, n] : {std::pair(0, 2), std::pair(3, 2), std::pair(1, 0)}) {
    o.shard = {k, n};
    const std::string message = fmt::format("--shard {}/{}: expected K/N with 1 ≤ K ≤ N", k, n);
    CHECK_THROWS_WITH_AS(golden::selectChecks(m, o), message.c_str(), std::invalid_argument);
  }
}

TEST_CASE("golden settings: an entry's own over the command line over the defaults over the programs'") {
  const GoldenManifest m = load(
      "defaults:\n"
      "  render: {size: 320x240, theme: light, raster: triangles}\n"
      "  tolerance: {threshold: 20}\n"
      "  state_tolerance: {velocity: 0.5}\n"
      "frames:\n"
      "  - {scenario: a.yaml, times: [1], render: {size: 64x48, raster: tiles}, tolerance: {max_share: 0.25}}\n"
      "  - {scenario: b.yaml, times: [1]}\n"
      "states:\n"
      "  - {scenario: c.yaml, times: [1], state_tolerance: {angle: 0.125}}\n");
  const scenario::GoldenEntry& own = m.frames[0];
  const scenario::GoldenEntry& plain = m.frames[1];
  const std::pair scenarioSize(160, 120);

  SUBCASE("the look") {
    render::RenderOptions look = golden::frameLookOf(m, own, {}, scenarioSize);
    CHECK(look.width == 64);  // its own
    CHECK(look.height == 48);
    CHECK(look.raster == render::Raster::tiles);
    CHECK(look.themeName == render::ThemeName::light);  // the default's
    CHECK(look.msaa == render::RenderOptions{}.msaa);   // the program's
    CHECK_FALSE(look.transparentBackground);

    look = golden::frameLookOf(m, plain, {}, scenarioSize);
    CHECK(look.width == 320);  // the defaults' over the scenario's
    CHECK(look.raster == render::Raster::triangles);

    CheckOverrides o;
    o.raster = render::Raster::automatic;
    CHECK(golden::frameLookOf(m, plain, o, scenarioSize).raster == render::Raster::automatic);  // over the default
    CHECK(golden::frameLookOf(m, own, o, scenarioSize).raster == render::Raster::tiles);        // under its own

    const GoldenManifest bare = load("frames:\n  - {scenario: a.yaml, times: [1]}\n");
    look = golden::frameLookOf(bare, bare.frames[0], {}, scenarioSize);
    CHECK(look.width == 160);  // the scenario's
    CHECK(look.height == 120);
    CHECK(look.themeName == render::ThemeName::dark);
    CHECK(look.raster == render::Raster::automatic);
  }

  SUBCASE("the frame tolerance") {
    render::CompareTolerance t = golden::compareToleranceOf(m, own, {});
    CHECK(t.threshold == 20);   // the default's
    CHECK(t.maxShare == 0.25);  // its own
    t = golden::compareToleranceOf(m, plain, {});
    CHECK(t.threshold == 20);
    CHECK(t.maxShare == render::CompareTolerance{}.maxShare);  // `particles compare`'s

    CheckOverrides o;
    o.threshold = 3;
    o.maxShare = 0.5;
    t = golden::compareToleranceOf(m, own, o);
    CHECK(t.threshold == 3);    // the command line over the default
    CHECK(t.maxShare == 0.25);  // its own over the command line
    t = golden::compareToleranceOf(m, plain, o);
    CHECK(t.maxShare == 0.5);  // the command line over the program's
  }

  SUBCASE("the state tolerance") {
    const golden::StateTolerance t = golden::stateCompareToleranceOf(m, m.states[0]);
    CHECK(t.angle == 0.125);                                               // its own
    CHECK(t.velocity == 0.5);                                              // the default's
    CHECK(t.position == scenario::kDefaultGoldenStateTolerance.position);  // the built-in ones
    CHECK(t.omega == scenario::kDefaultGoldenStateTolerance.omega);
  }

  SUBCASE("the laid settings keep where each was written") {
    const scenario::GoldenRenderSettings laid = scenario::renderSettingsOf(m, own);
    REQUIRE(laid.theme);
    CHECK(laid.theme->at.keyPath == "defaults.render.theme");
    REQUIRE(laid.raster);
    CHECK(laid.raster->at.keyPath == "frames[0].render.raster");
    CHECK_FALSE(laid.msaa);
  }
}

TEST_CASE("golden settings: names the renderer does not take are refused where the manifest writes them") {
  auto messageOf = [](const std::string& yaml) -> std::string {
    try {
      golden::checkRenderSettings(load(yaml));
    } catch (const scenario::ScenarioError& e) {
      return e.keyPath() + ": " + e.message();
    }
    return "accepted";
  };
  CHECK(messageOf("defaults:\n  render: {theme: sepia}\nframes:\n  - {scenario: a.yaml, times: [1]}\n") ==
        "defaults.render.theme: expected dark or light, got 'sepia'");
  CHECK(messageOf("frames:\n  - {scenario: a.yaml, times: [1], render: {raster: dots}}\n") ==
        "frames[0].render.raster: expected auto, triangles, tiles, resident, cpu, got 'dots'");
  CHECK(messageOf("frames:\n  - {scenario: a.yaml, times: [1], render: {background: none}}\n") ==
        "frames[0].render.background: expected theme or transparent, got 'none'");
  CHECK(messageOf("frames:\n  - {scenario: a.yaml, times: [1], render: {theme: light, background: transparent, "
                  "raster: tiles, size: 8x8, msaa: 16}}\n") == "accepted");
}

TEST_CASE("look options: each reads what it writes, and refuses what `particles render` refuses") {
  render::RenderOptions look;
  look.width = 64;
  look.height = 48;
  CHECK(render::lookWords(look) == std::vector<std::string>{"--size", "64x48", "--msaa", "4", "--theme", "dark"});

  look.msaa = 16;
  look.themeName = render::ThemeName::light;
  look.transparentBackground = true;
  look.raster = render::Raster::tiles;
  look.particleRadius = {0.025, render::Length::Unit::world};
  const std::vector<std::string> words = render::lookWords(look);
  CHECK(words == std::vector<std::string>{"--size", "64x48", "--msaa", "16", "--theme", "light", "--background",
                                          "transparent", "--raster", "tiles", "--particle-radius", "0.025m"});
  render::RenderOptions read;
  for (size_t i = 0; i < words.size(); i += 2) CHECK(render::lookOption(words[i]).read(words[i + 1], read));
  CHECK(render::lookWords(read) == words);

  const std::vector<std::pair<std::string, std::string>> refused = {{"--size", "64"},
                                                                    {"--size", "0x48"},
                                                                    {"--size", "64x48x2"},
                                                                    {"--msaa", "3"},
                                                                    {"--msaa", "4x"},
                                                                    {"--theme", "Dark"},
                                                                    {"--background", ""},
                                                                    {"--raster", "tile"},
                                                                    {"--particle-radius", "-1px"},
                                                                    {"--particle-radius", "2cm"}};
  for (const auto& option : refused) {
    CAPTURE(option.first);
    CAPTURE(option.second);
    render::RenderOptions untouched;
    CHECK_FALSE(render::lookOption(option.first).read(option.second, untouched));
    CHECK(render::lookWords(untouched) == render::lookWords(render::RenderOptions{}));
  }
  CHECK(render::lookOption("--size").read("640X360", read));
  CHECK(read.width == 640);
  CHECK(render::lookOption("--particle-radius").read("3", read));  // a bare number is pixels
  CHECK(read.particleRadius.unit == render::Length::Unit::pixels);
  CHECK(render::lookOption("--msaa").expected == "1 (off), 2, 4, 8 or 16");
  CHECK_THROWS_AS(render::lookOption("--fps"), std::invalid_argument);
}

TEST_CASE("reproduce commands: the exact words of render, compare, check and update") {
  const GoldenManifest m = load(
      "frames:\n"
      "  - scenario: ../scenarios/swing.yaml\n"
      "    times: [0.5]\n"
      "    set: {\"particles[1].mass\": 2, \"forces[0].g\": [0, -1]}\n");
  CheckOptions o;
  o.manifestGiven = "golden/my golden.yaml";
  o.program = "build/particles";
  render::RenderOptions look;
  look.width = 32;
  look.height = 24;
  const render::CompareTolerance tolerance{12, 0.00025};

  CHECK(golden::renderCommand(o, m.frames[0], "swing_t0.5", "0.5", look) ==
        "build/particles render scenarios/swing.yaml -o swing_t0.5.png --at 0.5 --size 32x24 --msaa 4 "
        "--theme dark --set 'particles[1].mass=2' --set 'forces[0].g=[0, -1]'");
  CHECK(golden::compareCommand(o, "dir/swing_t0.5.png", "swing_t0.5", tolerance) ==
        "build/particles compare dir/swing_t0.5.png swing_t0.5.png --threshold 12 --max-share 0.00025 --diff "
        "swing_t0.5.diff.png");
  CHECK(golden::checkCommand(o, "swing_t0.5") ==
        "build/particles golden check 'golden/my golden.yaml' --only swing_t0.5");
  CHECK(golden::noReferenceYet(o, "dir/swing_t0.5.png") ==
        "no reference dir/swing_t0.5.png yet: create it with build/particles golden update 'golden/my golden.yaml' "
        "--missing");

  // The run's backend and overrides follow the check and render commands.
  o.gl.backend = render::GlBackend::osmesa;
  o.overrides.raster = render::Raster::tiles;
  o.overrides.maxShare = 0.0005;
  look.raster = render::Raster::tiles;
  look.transparentBackground = true;
  CHECK(golden::renderCommand(o, m.frames[0], "swing_t0.5", "0.5", look) ==
        "build/particles render scenarios/swing.yaml -o swing_t0.5.png --at 0.5 --size 32x24 --msaa 4 "
        "--theme dark --background transparent --raster tiles --set 'particles[1].mass=2' --set 'forces[0].g=[0, -1]' "
        "--gl osmesa");
  CHECK(golden::checkCommand(o, "swing_t0.5") ==
        "build/particles golden check 'golden/my golden.yaml' --only swing_t0.5 --raster tiles --max-share 0.0005 "
        "--gl osmesa");
  CHECK(o.overrides.text() == "--raster tiles --max-share 0.0005");
  CHECK(golden::glWords({}).empty());
}
