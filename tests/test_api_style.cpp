// Styles through the public C++ API (include/particles/style.hpp, Scenario::setStyle): a Style
// struct and a style file's text merge over a scenario's own section as `particles render --style
// FILE` merges the file, with its checks and messages, and Renderer::render draws them as
// `particles render --at` does, byte for byte, trails and a followed camera included.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include <particles/particles.hpp>

#include "cli_support.hpp"
#include "render/png_io.hpp"
#include "source_tree.hpp"

using namespace particles::test;

namespace {

// The scene and its style file, shared with the Python tests (tests/python/test_style.py).
const std::string kStyledScene = slurp(std::filesystem::path(kSource) / "tests/fixtures/styled_api.yaml");
const std::string kStyledLook = slurp(std::filesystem::path(kSource) / "tests/fixtures/styled_api_look.yaml");

// The style file's keys as a Style.
particles::Style styledLookStruct() {
  particles::Style s;
  s.particles = {.colorBy = "speed", .colormap = "magma_r", .range = particles::ColorRange{.min = 0, .max = 2}};
  s.springs = {.colorBy = "tension", .colormap = "coolwarm", .width = "2px"};
  s.bodies = {.outline = "#ffffff", .colorBy = "angular_speed", .range = particles::ColorRange{}};
  s.colorbar = particles::ColorbarStyle{.for_ = "particles", .label = "speed (m/s)", .position = "left"};
  s.title = "Cloth: \"styled\"";
  s.scaleBar = true;
  s.select = {
      {.particles = {"cloth[0][*]"}, .color = "orange", .radius = "5px"},
      {.particles = {"cloth[4][2]", "cloth[4][3]"},
       .trail = particles::TrailStyle{.seconds = 0.5, .width = "2px"},
       .arrow = particles::ArrowStyle{.of = "velocity", .scale = 0.2, .max = "40px"},
       .label = "corner"},
      {.bodies = {"box"},
       .trail = particles::TrailStyle{.seconds = std::numeric_limits<double>::infinity(), .color = "#ff000080"},
       .arrow = particles::ArrowStyle{.of = "force"}},
  };
  return s;
}

// The frame `particles render SCENE --style STYLE --at T` writes (empty STYLE: without --style).
particles::render::Image styledProgramFrame(const Scratch& scratch, const std::string& scene, const std::string& style,
                                            const std::string& at, const std::string& options = "") {
  const std::string styleOption = style.empty() ? "" : " --style " + style;
  const Result r = scratch.run("render " + scene + styleOption + " --at " + at + " -o cli.png --quiet " + options);
  REQUIRE_MESSAGE(r.code == 0, r.err);
  return particles::render::readPng(scratch.dir / "cli.png");
}

}  // namespace

// One truth: a Style, a style file's text and `render --style FILE` draw the same frames, and the
// simulation's history gives the trails and the followed camera of a render's run from its start.
TEST_CASE("api style: setStyle(Style) and setStyle(yaml) draw the frames of render --style --at, byte for byte") {
  Scratch scratch;
  const std::string scene = scratch.write("scene.yaml", kStyledScene).string();
  scratch.write("look.yaml", kStyledLook);
  particles::Scenario byStruct = particles::Scenario::fromText(kStyledScene, "scene.yaml");
  byStruct.setStyle(styledLookStruct());
  particles::Scenario byText = particles::Scenario::fromText(kStyledScene, "scene.yaml");
  byText.setStyle(kStyledLook);
  particles::Simulation structSim(byStruct), textSim(byText);
  particles::Renderer renderer;  // the scenario's size, the command's defaults
  for (const char* at : {"0", "0.3", "0.75"}) {
    CAPTURE(at);
    const particles::render::Image expected = styledProgramFrame(scratch, scene, "look.yaml", at);
    structSim.advanceTo(std::strtod(at, nullptr));
    textSim.advanceTo(std::strtod(at, nullptr));
    const particles::Image fromStruct = renderer.render(structSim);
    CHECK(fromStruct.width == 160);
    CHECK(fromStruct.rgba == expected.rgba);
    CHECK(renderer.render(textSim).rgba == expected.rgba);
  }
  // The scenario's own style, without a style file: its height colours and title.
  particles::Simulation own(particles::Scenario::fromText(kStyledScene, "scene.yaml"));
  own.advanceTo(0.5);
  CHECK(renderer.render(own).rgba == styledProgramFrame(scratch, scene, "", "0.5").rgba);
}

TEST_CASE("api style: the Renderer's settings draw the style, and each frame is fitted to itself") {
  Scratch scratch;
  // fit: all instead of follow, and automatic ranges: both are the frame's own, as `render --at`'s.
  const std::string follow = "follow: \"cloth[4][2]\", smoothing: 0.2";
  std::string fitted = kStyledScene;
  fitted.replace(fitted.find(follow), follow.size(), "fit: all, margin: 0.05");
  const std::string scene = scratch.write("fit.yaml", fitted).string();
  scratch.write("auto.yaml", "particles: {color_by: speed}\nbodies: {color_by: speed}\ncolorbar: true\n");
  particles::Scenario scenario = particles::Scenario::fromText(fitted, "fit.yaml");
  scenario.setStyle("particles: {color_by: speed}\nbodies: {color_by: speed}\ncolorbar: true\n");
  particles::Simulation sim(scenario);
  particles::Renderer light({.width = 200, .height = 100, .theme = particles::Theme::light, .msaa = 2});
  for (const char* at : {"0.2", "1.1"}) {
    CAPTURE(at);
    sim.advanceTo(std::strtod(at, nullptr));
    CHECK(light.render(sim).rgba ==
          styledProgramFrame(scratch, scene, "auto.yaml", at, "--size 200x100 --theme light --msaa 2").rgba);
  }
}

TEST_CASE("api style: a bad style is the style file's ScenarioError, and the scenario stays as it was") {
  Scratch scratch;
  const std::string scene = scratch.write("scene.yaml", kStyledScene).string();
  particles::Scenario scenario = particles::Scenario::fromText(kStyledScene, "scene.yaml");
  struct Case {
    particles::Style style;
    std::string yaml, keyPath;
  };
  const Case cases[] = {
      {{.particles = {.colorBy = "sped"}}, "particles: {color_by: sped}", "style.particles.color_by"},
      {{.springs = {.width = "-2px"}}, "springs: {width: -2px}", "style.springs.width"},
      {{.bodies = {.color = "steelblu"}}, "bodies: {color: steelblu}", "style.bodies.color"},
      {{.particles = {.range = particles::ColorRange{.min = 2, .max = 1}}},
       "particles: {range: {min: 2, max: 1}}",
       "style.particles.range"},
      {{.select = {{.particles = {"clth"}}}}, "select: [{particles: clth}]", "style.select[0].particles"},
      {{.select = {{.bodies = {"box"}, .trail = particles::TrailStyle{.seconds = -1}}}},
       "select: [{bodies: box, trail: {seconds: -1}}]",
       "style.select[0].trail.seconds"},
      {{.colorbar = particles::ColorbarStyle{.for_ = "bodies"}}, "colorbar: {for: bodies}", "style.colorbar.for"},
      {{.title = std::string("two\nlines")}, "title: \"two\\nlines\"", "style.title"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.yaml);
    scratch.write("bad.yaml", c.yaml + "\n");
    const Result r = scratch.run("check " + scene + " --style bad.yaml");
    REQUIRE(r.code == 2);
    try {
      scenario.setStyle(c.style);
      FAIL("no error");
    } catch (const particles::ScenarioError& e) {
      CHECK(e.file() == "style");
      CHECK(e.line() == 0);
      CHECK(e.keyPath() == c.keyPath);
      CHECK_MESSAGE(r.err.find("bad.yaml:1:") != std::string::npos, r.err);
      CHECK_MESSAGE(r.err.find(c.keyPath + ": " + e.message()) != std::string::npos, r.err << " vs " << e.message());
      CHECK(std::string(e.what()) == "style: error: " + c.keyPath + ": " + e.message());
    }
    try {
      scenario.setStyle(c.yaml);
      FAIL("no error");
    } catch (const particles::ScenarioError& e) {
      // The text's own place, as the program gives the file's.
      CHECK_MESSAGE(r.err.find("bad.yaml" + std::string(e.what()).substr(5)) != std::string::npos,
                    r.err << " vs " << e.what());
    }
  }
  // The unknown quantity's message suggests the closest name, as the file's does.
  CHECK_THROWS_WITH_AS(scenario.setStyle(cases[0].style),
                       doctest::Contains("unknown particle quantity 'sped'; did you mean 'speed'?"),
                       particles::ScenarioError);
  // Nothing was kept: the scenario draws its own style.
  particles::Simulation sim(scenario);
  CHECK(particles::Renderer().render(sim).rgba == styledProgramFrame(scratch, scene, "", "0").rgba);
}

TEST_CASE("api style: setStyle replaces the style before it, an empty one takes it away, and copies keep theirs") {
  Scratch scratch;
  const std::string scene = scratch.write("scene.yaml", kStyledScene).string();
  scratch.write("speed.yaml", "particles: {color_by: speed}\n");
  scratch.write("clear.yaml", "particles: {color_by: ~, color: red}\ntitle: \"a: b # c\"\n");
  particles::Scenario scenario = particles::Scenario::fromText(kStyledScene, "scene.yaml");
  particles::Renderer renderer({.msaa = 1});
  auto frame = [&](const particles::Scenario& s) {
    particles::Simulation sim(s);
    sim.advanceTo(0.4);
    return renderer.render(sim).rgba;
  };
  const auto own = frame(scenario);
  scenario.setStyle(particles::Style{.particles = {.colorBy = "speed"}});
  const particles::Scenario copy = scenario;
  const auto speed = frame(scenario);
  CHECK(speed == styledProgramFrame(scratch, scene, "speed.yaml", "0.4", "--msaa 1").rgba);
  CHECK(speed != own);
  // A later style replaces the first (not merged over it); null takes the scenario's key away.
  scenario.setStyle("particles: {color_by: ~, color: red}\ntitle: \"a: b # c\"\n");
  CHECK(frame(scenario) == styledProgramFrame(scratch, scene, "clear.yaml", "0.4", "--msaa 1").rgba);
  // Given after set(), merged before it, as --style before --set.
  scratch.write("title.yaml", "title: style\n");
  scenario.set("style.title", "set").setStyle(particles::Style{.title = "style"});
  CHECK(frame(scenario) ==
        styledProgramFrame(scratch, scene, "title.yaml", "0.4", "--msaa 1 --set style.title=set").rgba);
  scenario.set("style.title", "own").setStyle(particles::Style{});
  CHECK(frame(scenario) == own);
  scenario.setStyle("");
  CHECK(frame(scenario) == own);
  CHECK(frame(copy) == speed);
}

TEST_CASE("api style: trails past their limit fail the frame, not the simulation, and a bad RangeScale is refused") {
  // 30 particles' whole-run trails over 10⁶ steps: more than style::kMaxTrailSamples.
  particles::Scenario scenario = particles::Scenario::fromText(kStyledScene, "scene.yaml");
  scenario.set("duration", 10000).setStyle("select: [{particles: cloth, trail: {seconds: all}}]");
  particles::Simulation sim(scenario);
  sim.step(3);
  CHECK_THROWS_WITH_AS(particles::Renderer().render(sim), doctest::Contains("style.select[0].trail: the trails"),
                       particles::Error);
  particles::Style bad;
  bad.particles.range = particles::ColorRange{.scale = static_cast<particles::RangeScale>(7)};
  CHECK_THROWS_WITH_AS(scenario.setStyle(bad), doctest::Contains("particles.range.scale is not a RangeScale"),
                       particles::ArgumentError);
  particles::Scenario moved = std::move(scenario);
  CHECK_THROWS_AS(scenario.setStyle(particles::Style{}), particles::ArgumentError);  // NOLINT(bugprone-use-after-move)
  CHECK_THROWS_AS(scenario.setStyle("title: x"), particles::ArgumentError);          // NOLINT(bugprone-use-after-move)
}
