// The scenario's `style` section and render.view's camera modes (docs/scenarios.md, "Style" and
// "Render"): every key read into style::Style or style::ViewStyle with its numbers and resolved
// indices, and every refusal naming the file, line, column and key path, with a suggestion where a
// name is misspelt. Then the ways a style reaches the loader besides the file: --set style.… and
// a style file (`render --style`, `check --style`) merged over the section, whose errors name it.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "cli_support.hpp"
#include "scenario/scenario.hpp"
#include "source_tree.hpp"

using namespace particles;
using namespace particles::scenario;

namespace {

// Particle 0 is bob; grid `cloth` (3 columns, 2 rows) holds particles 1 … 6, cloth[r][c] being
// 1 + 3r + c; bodies link0 and link1 are 0 and 1. Lines 1 to 8; a case's own lines start at 9.
const std::string kStyleBase =
    "name: t\n"
    "particles:\n"
    "  - {name: bob, pos: [1, 0]}\n"
    "grids:\n"
    "  - {name: cloth, origin: [0, 2], size: [3, 2], springs: {structural: {ks: 100}}}\n"
    "rigid_bodies:\n"
    "  - {name: link0, pos: [0, 0], size: [1, 0.2]}\n"
    "  - {name: link1, pos: [1, 0], size: [1, 0.2]}\n";

struct StyleRefusal {
  std::string file;
  int line = -1, column = -1;
  std::string keyPath, message, origin, what;
};

StyleRefusal styleRefusalOf(const std::string& yaml, const std::vector<Override>& overrides = {},
                            const StyleFile* styleFile = nullptr, const SceneLimits& limits = {}) {
  try {
    loadScenarioText(yaml, "s.yaml", overrides, limits, styleFile);
  } catch (const ScenarioError& e) {
    return {e.file(), e.line(), e.column(), e.keyPath(), e.message(), e.origin(), e.what()};
  }
  FAIL("expected a ScenarioError for:\n" << yaml);
  return {};
}

// The 1-based column where `marker` starts on line `line` of `text`: where an error should point.
int columnOf(const std::string& text, int line, std::string_view marker) {
  size_t start = 0;
  for (int k = 1; k < line; ++k) start = text.find('\n', start) + 1;
  const std::string_view row = std::string_view(text).substr(start, text.find('\n', start) - start);
  const size_t at = row.find(marker);
  REQUIRE_MESSAGE(at != std::string_view::npos, "no '" << marker << "' on line " << line << ": " << row);
  return int(at) + 1;
}

// `lines` appended to kStyleBase fail on line `line` of s.yaml where `marker` starts, at `keyPath`,
// with `fragment` in the message.
void expectStyleError(const std::string& lines, int line, std::string_view marker, const std::string& keyPath,
                      const std::string& fragment) {
  const StyleRefusal r = styleRefusalOf(kStyleBase + lines);
  CAPTURE(lines);
  CAPTURE(r.what);
  CHECK(r.file == "s.yaml");
  CHECK(r.line == line);
  CHECK(r.column == columnOf(kStyleBase + lines, line, marker));
  CHECK(r.keyPath == keyPath);
  CHECK_MESSAGE(r.message.find(fragment) != std::string::npos, r.message);
}

Scenario loadedStyled(const std::string& lines, const std::vector<Override>& overrides = {},
                      const StyleFile* styleFile = nullptr) {
  return loadScenarioText(kStyleBase + lines, "s.yaml", overrides, {}, styleFile);
}

std::vector<int> indices(std::initializer_list<int> values) {
  return values;
}

}  // namespace

TEST_CASE("style: without a style section the style is plain and the camera fixed") {
  const Scenario s = loadedStyled("");
  CHECK(s.style.isPlain());
  CHECK(s.render.view.mode == style::ViewStyle::Mode::fixed);
}

TEST_CASE("style: the shape classes' keys are read with their numbers") {
  const Scenario s = loadedStyled(
      "style:\n"
      "  particles: {color_by: speed, colormap: viridis, range: auto, radius: 3px}\n"
      "  springs: {color_by: tension, colormap: coolwarm, range: [-0.2, 0.5], width: 0.01m}\n"
      "  bodies: {outline: white, color_by: angular_speed, colormap: magma_r, range: {min: 0.5, max: 20, scale: "
      "log}}\n"
      "  title: \"Cloth, RK4, dt = 0.01 s\"\n"
      "  scale_bar: true\n");
  const style::Style& st = s.style;
  CHECK(st.particles.colorBy == style::ParticleQuantity::speed);
  CHECK(st.particles.colormap == style::Colormap{style::ColormapName::viridis, false});
  CHECK(st.particles.range.automatic);
  CHECK(st.particles.radius == style::Length{3.0, true});
  CHECK_FALSE(st.particles.color);
  CHECK(st.springs.colorBy == style::SpringQuantity::tension);
  CHECK(st.springs.colormap == style::Colormap{style::ColormapName::coolwarm, false});
  CHECK(st.springs.range == style::Range{.automatic = false, .lo = -0.2, .hi = 0.5, .logScale = false});
  CHECK(st.springs.rangeGiven);
  CHECK(st.springs.width == style::Length{0.01, false});
  CHECK(st.bodies.outline == style::Color{255, 255, 255, 255});
  CHECK(st.bodies.colorBy == style::BodyQuantity::angularSpeed);
  CHECK(st.bodies.colormap == style::Colormap{style::ColormapName::magma, true});
  CHECK(st.bodies.range == style::Range{.automatic = false, .lo = 0.5, .hi = 20.0, .logScale = true});
  CHECK(st.title == "Cloth, RK4, dt = 0.01 s");
  CHECK(st.scaleBar);
  CHECK_FALSE(st.isPlain());
}

TEST_CASE("style: colours by name and in hex, lengths in pixels and metres, automatic ranges on a log scale") {
  const Scenario s = loadedStyled(
      "style:\n"
      "  particles: {color: Orange, radius: 0.02, range: {scale: log}}\n"
      "  springs: {color: \"#ffffff80\", width: 1px}\n"
      "  bodies: {color: \"#4682B4\"}\n");
  CHECK(s.style.particles.color == style::Color{255, 165, 0, 255});
  CHECK(s.style.particles.radius == style::Length{0.02, false});
  CHECK(s.style.particles.range.automatic);
  CHECK(s.style.particles.range.logScale);
  CHECK(s.style.springs.color == style::Color{255, 255, 255, 128});
  CHECK(s.style.springs.width == style::Length{1.0, true});
  CHECK_FALSE(s.style.springs.rangeGiven);  // the strain's default range stays
  CHECK(s.style.springs.range == style::SpringStyle{}.range);
  CHECK(s.style.bodies.color == style::Color{70, 130, 180, 255});
}

TEST_CASE("style: selections resolve to sorted particle and body indices, with their trails, arrows and labels") {
  const Scenario s = loadedStyled(
      "style:\n"
      "  select:\n"
      "    - {particles: \"cloth[0][*]\", color: orange, radius: 5px}\n"
      "    - {particles: \"cloth[-1][2]\", trail: {seconds: 2, width: 2px}, arrow: velocity, label: corner}\n"
      "    - {bodies: link1, trail: {seconds: all, color: red}, arrow: {of: force, scale: 0.05, max: 60px}, "
      "label: \"end\"}\n"
      "    - {particles: [\"#0\", \"cloth[1][0]\", cloth], color: \"#00ff00\"}\n"
      "    - {bodies: [link1, link0]}\n");
  const std::vector<style::Selection>& sel = s.style.select;
  REQUIRE(sel.size() == 5);
  CHECK(sel[0].particlesSelector == "cloth[0][*]");
  CHECK(sel[0].particles == indices({1, 2, 3}));
  CHECK(sel[0].bodies.empty());
  CHECK(sel[0].color == style::Color{255, 165, 0, 255});
  CHECK(sel[0].radius == style::Length{5.0, true});
  CHECK(sel[1].particles == indices({6}));
  REQUIRE(sel[1].trail);
  CHECK(sel[1].trail->seconds == 2.0);
  CHECK(sel[1].trail->width == style::Length{2.0, true});
  REQUIRE(sel[1].arrow);
  CHECK(sel[1].arrow->of == style::ArrowQuantity::velocity);
  CHECK(sel[1].arrow->scale == style::ArrowStyle{}.scale);
  CHECK(sel[1].label == "corner");
  CHECK(sel[2].bodiesSelector == "link1");
  CHECK(sel[2].bodies == indices({1}));
  CHECK(sel[2].particles.empty());
  REQUIRE(sel[2].trail);
  CHECK(std::isinf(sel[2].trail->seconds));
  CHECK(sel[2].trail->color == style::Color{255, 0, 0, 255});
  REQUIRE(sel[2].arrow);
  CHECK(sel[2].arrow->of == style::ArrowQuantity::force);
  CHECK(sel[2].arrow->scale == 0.05);
  CHECK(sel[2].arrow->max == style::Length{60.0, true});
  CHECK(sel[2].label == "end");
  CHECK(sel[3].particles == indices({0, 1, 2, 3, 4, 5, 6}));  // duplicates once
  CHECK(sel[4].bodies == indices({0, 1}));
}

TEST_CASE("style: a colour bar names its shapes, or takes the first class coloured by a quantity") {
  SUBCASE("for, label and position") {
    const Scenario s = loadedStyled(
        "style:\n  particles: {color_by: speed}\n  colorbar: {for: particles, label: \"speed (m/s)\", "
        "position: left}\n");
    REQUIRE(s.style.colorbar);
    CHECK(s.style.colorbar->subject == style::ColorbarSubject::particles);
    CHECK(s.style.colorbar->label == "speed (m/s)");
    CHECK(s.style.colorbar->position == style::ColorbarPosition::left);
  }
  SUBCASE("without for: the springs, coloured by strain unless given one colour") {
    const Scenario s = loadedStyled("style:\n  colorbar: true\n");
    REQUIRE(s.style.colorbar);
    CHECK(s.style.colorbar->subject == style::ColorbarSubject::springs);
    CHECK(s.style.colorbar->position == style::ColorbarPosition::right);
  }
  SUBCASE("without for: particles come first") {
    const Scenario s = loadedStyled("style:\n  particles: {color_by: height}\n  colorbar: {position: bottom}\n");
    REQUIRE(s.style.colorbar);
    CHECK(s.style.colorbar->subject == style::ColorbarSubject::particles);
  }
  SUBCASE("false: none") {
    CHECK_FALSE(loadedStyled("style:\n  colorbar: false\n").style.colorbar);
  }
}

TEST_CASE("style: render.view's camera modes, their points resolved") {
  SUBCASE("fixed: center and height") {
    const Scenario s = loadedStyled("render: {view: {center: [1, 2], height: 4}}\n");
    CHECK(s.render.view.mode == style::ViewStyle::Mode::fixed);
    CHECK(s.render.viewCenter == Vec2(1, 2));
    CHECK(s.render.viewHeight == 4.0);
  }
  SUBCASE("fit: all") {
    const Scenario s = loadedStyled("render: {view: {fit: all, margin: 0.2}}\n");
    CHECK(s.render.view.mode == style::ViewStyle::Mode::fit);
    CHECK(s.render.view.fitAll);
    CHECK(s.render.view.margin == 0.2);
  }
  SUBCASE("fit: names") {
    const Scenario s = loadedStyled("render: {view: {fit: [bob, \"cloth[1][*]\", link1]}}\n");
    CHECK(s.render.view.mode == style::ViewStyle::Mode::fit);
    CHECK_FALSE(s.render.view.fitAll);
    CHECK(s.render.view.fitNames == std::vector<std::string>{"bob", "cloth[1][*]", "link1"});
    CHECK(s.render.view.fitParticles == indices({0, 4, 5, 6}));
    CHECK(s.render.view.fitBodies == indices({1}));
    CHECK(s.render.view.margin == style::ViewStyle{}.margin);
  }
  SUBCASE("follow: a grid particle") {
    const Scenario s = loadedStyled("render:\n  view: {follow: \"cloth[1][2]\", smoothing: 0.25}\n");
    CHECK(s.render.view.mode == style::ViewStyle::Mode::follow);
    CHECK(s.render.view.followName == "cloth[1][2]");
    CHECK(s.render.view.followParticle == 6);
    CHECK(s.render.view.followBody == -1);
    CHECK(s.render.view.smoothing == 0.25);
  }
  SUBCASE("follow: a body") {
    const Scenario s = loadedStyled("render:\n  view: {follow: link0}\n");
    CHECK(s.render.view.followParticle == -1);
    CHECK(s.render.view.followBody == 0);
    CHECK(s.render.view.smoothing == style::ViewStyle{}.smoothing);
  }
  SUBCASE("keys: what a key leaves out is the key before's, the view's first") {
    const Scenario s = loadedStyled(
        "render:\n"
        "  view:\n"
        "    center: [1, 1]\n"
        "    height: 5\n"
        "    keys: [{t: 0}, {t: 2, center: [3, 0]}, {t: 4.5, height: 2}]\n");
    CHECK(s.render.view.mode == style::ViewStyle::Mode::keys);
    REQUIRE(s.render.view.keys.size() == 3);
    CHECK(s.render.view.keys[0].t == 0.0);
    CHECK(s.render.view.keys[0].center == Vec2(1, 1));
    CHECK(s.render.view.keys[0].height == 5.0);
    CHECK(s.render.view.keys[1].t == 2.0);
    CHECK(s.render.view.keys[1].center == Vec2(3, 0));
    CHECK(s.render.view.keys[1].height == 5.0);
    CHECK(s.render.view.keys[2].center == Vec2(3, 0));
    CHECK(s.render.view.keys[2].height == 2.0);
  }
}

TEST_CASE("style error: an unknown key suggests the closest one") {
  expectStyleError("style:\n  particles: {colr_by: speed}\n", 10, "colr_by", "style.particles.colr_by",
                   "unknown key 'colr_by'; did you mean 'color_by'?");
  expectStyleError("style:\n  scalebar: true\n", 10, "scalebar", "style.scalebar", "did you mean 'scale_bar'?");
  expectStyleError("render: {view: {folow: bob}}\n", 9, "folow", "render.view.folow", "did you mean 'follow'?");
}

TEST_CASE("style error: an unknown quantity or colormap suggests the closest name") {
  expectStyleError("style:\n  particles: {color_by: speeed}\n", 10, "speeed", "style.particles.color_by",
                   "unknown particle quantity 'speeed'; did you mean 'speed'? (one of speed, velocity_x");
  expectStyleError("style:\n  springs: {color_by: stran}\n", 10, "stran", "style.springs.color_by",
                   "unknown spring quantity 'stran'; did you mean 'strain'?");
  expectStyleError("style:\n  bodies: {color_by: angular_sped}\n", 10, "angular_sped", "style.bodies.color_by",
                   "did you mean 'angular_speed'?");
  expectStyleError("style:\n  particles: {colormap: virdis}\n", 10, "virdis", "style.particles.colormap",
                   "unknown colormap 'virdis'; did you mean 'viridis'?");
  expectStyleError("style:\n  springs: {colormap: coolwarm_R}\n", 10, "coolwarm_R", "style.springs.colormap",
                   "did you mean 'coolwarm_r'?");
}

TEST_CASE("style error: a bad colour, by name or in hex") {
  expectStyleError("style:\n  particles: {color: orang}\n", 10, "orang", "style.particles.color",
                   "unknown colour 'orang'; did you mean 'orange'?");
  expectStyleError("style:\n  bodies: {outline: \"#12345\"}\n", 10, "\"#12345", "style.bodies.outline",
                   "expected #rrggbb or #rrggbbaa (6 or 8 hex digits), got '#12345'");
}

TEST_CASE("style error: ranges") {
  expectStyleError("style:\n  particles: {range: [2, 1]}\n", 10, "[2, 1]", "style.particles.range",
                   "expected lo < hi, got lo = 2 and hi = 1");
  expectStyleError("style:\n  springs: {range: {min: 1, max: 1}}\n", 10, "{min: 1", "style.springs.range",
                   "expected lo < hi");
  expectStyleError("style:\n  particles: {range: [.nan, 1]}\n", 10, ".nan", "style.particles.range[0]",
                   "expected a finite number");
  expectStyleError("style:\n  particles: {range: [0, .inf]}\n", 10, ".inf", "style.particles.range[1]",
                   "expected a finite number");
  expectStyleError("style:\n  bodies: {range: {min: 0, max: 10, scale: log}}\n", 10, "0, max", "style.bodies.range.min",
                   "a log scale needs min > 0, got 0");
  expectStyleError("style:\n  bodies: {range: {max: 10}}\n", 10, "10}}", "style.bodies.range.max",
                   "expected both 'min' and 'max', or neither");
  expectStyleError("style:\n  bodies: {range: {scale: logarithmic}}\n", 10, "logarithmic", "style.bodies.range.scale",
                   "unknown scale 'logarithmic'");
  expectStyleError("style:\n  particles: {range: automatic}\n", 10, "automatic", "style.particles.range",
                   "expected auto, [lo, hi] or a map {min, max, scale}");
}

TEST_CASE("style error: lengths") {
  expectStyleError("style:\n  particles: {radius: 3 px}\n", 10, "3 px", "style.particles.radius",
                   "expected a length: 3px");
  expectStyleError("style:\n  springs: {width: 0px}\n", 10, "0px", "style.springs.width",
                   "expected a length > 0, got '0px'");
  expectStyleError("style:\n  springs: {width: -1}\n", 10, "-1", "style.springs.width", "expected a length > 0");
}

TEST_CASE("style error: a selector that names nothing, a body anchor, or the wrong kind of thing") {
  expectStyleError("style:\n  select:\n    - {particles: clth}\n", 11, "clth", "style.select[0].particles",
                   "reference 'clth': nothing is named 'clth'; did you mean 'cloth'?");
  expectStyleError(
      "style:\n  select:\n    - {bodies: \"link0@[0.2, 0]\"}\n", 11, "\"link0@", "style.select[0].bodies",
      "reference 'link0@[0.2, 0]' is a point on a rigid body; select the body by its name alone ('link0')");
  expectStyleError("style:\n  select:\n    - {particles: \"link0@[0.2, 0]\"}\n", 11, "\"link0@",
                   "style.select[0].particles", "reference 'link0@[0.2, 0]': rigid-body anchors are not allowed here");
  expectStyleError("style:\n  select:\n    - {particles: [bob, link1]}\n", 11, "link1", "style.select[0].particles[1]",
                   "'link1' is a rigid body, but only particles are allowed here");
  expectStyleError("style:\n  select:\n    - {bodies: bob}\n", 11, "bob", "style.select[0].bodies",
                   "reference 'bob' names particles; 'bodies' selects rigid bodies");
  expectStyleError("style:\n  select:\n    - {particles: \"cloth[2][0]\"}\n", 11, "\"cloth[2]",
                   "style.select[0].particles", "row 2 is out of range");
  expectStyleError("style:\n  select:\n    - {particles: bob, bodies: link0}\n", 11, "link0", "style.select[0].bodies",
                   "'particles' and 'bodies' both select");
  expectStyleError("style:\n  select:\n    - {color: red}\n", 11, "{color", "style.select[0]",
                   "expected 'particles' or 'bodies'");
  expectStyleError("style:\n  select:\n    - {bodies: link0, radius: 3px}\n", 11, "3px", "style.select[0].radius",
                   "'radius' is a particle's");
  expectStyleError("style:\n  select:\n    - {bodies: link0, trail: {seconds: ever}}\n", 11, "ever",
                   "style.select[0].trail.seconds", "expected a number of seconds > 0, or all");
  expectStyleError("style:\n  select:\n    - {bodies: link0, arrow: speed}\n", 11, "speed", "style.select[0].arrow",
                   "unknown arrow quantity 'speed'");
  expectStyleError("style:\n  select:\n    - {bodies: link0, arrow: {of: force, scale: 0}}\n", 11, "0}}",
                   "style.select[0].arrow.scale", "expected a number > 0, got 0");
}

TEST_CASE("style error: labels and titles are one printable line of at most kMaxLabelLength characters") {
  const std::string longest(style::kMaxLabelLength, 'x');
  CHECK(loadedStyled("style:\n  title: " + longest + "\n").style.title == longest);
  // Counted in code points: 200 × 'é' is 400 bytes and fits.
  std::string accented;
  for (size_t i = 0; i < style::kMaxLabelLength; ++i) accented += "é";
  CHECK(loadedStyled("style:\n  title: " + accented + "\n").style.title == accented);
  expectStyleError("style:\n  title: " + longest + "x\n", 10, "x", "style.title",
                   fmt::format("expected at most {} characters (Unicode code points), got {}", style::kMaxLabelLength,
                               style::kMaxLabelLength + 1));
  expectStyleError("style:\n  select:\n    - {bodies: link0, label: \"a\\x1bb\"}\n", 11, "\"a", "style.select[0].label",
                   "a control character or a byte that is not UTF-8 (shown escaped: 'a\\x1bb')");
  expectStyleError("style:\n  title: \"two\\nlines\"\n", 10, "\"two", "style.title", "a line break at character 4");
  expectStyleError("style:\n  colorbar: {label: \"a\\tb\"}\n", 10, "\"a", "style.colorbar.label",
                   "a tab at character 2");
}

TEST_CASE("style error: a colour bar needs shapes coloured by a quantity") {
  expectStyleError("style:\n  colorbar: {for: particles}\n", 10, "particles}", "style.colorbar.for",
                   "the particles are not coloured by a quantity (style.particles.color_by is not set)");
  expectStyleError("style:\n  springs: {color: white}\n  colorbar: {for: springs}\n", 11, "springs}",
                   "style.colorbar.for", "the springs have one colour");
  expectStyleError("style:\n  springs: {color: white}\n  colorbar: {position: top}\n", 11, "{position",
                   "style.colorbar", "a colour bar explains shapes coloured by a quantity, and none are");
  expectStyleError("style:\n  particles: {color_by: speed, color: red}\n", 10, "red}", "style.particles.color",
                   "'color' and 'color_by' both colour these shapes");
  // A scene without springs has no springs' colour bar.
  const StyleRefusal r =
      styleRefusalOf("name: t\nparticles: [{name: a, pos: [0, 0]}]\nstyle: {colorbar: {for: springs}}\n");
  CHECK(r.line == 3);
  CHECK(r.keyPath == "style.colorbar.for");
  CHECK(r.message.find("the scene has no springs") != std::string::npos);
}

TEST_CASE("style error: the camera's modes") {
  expectStyleError("render:\n  view: {fit: all, follow: bob}\n", 10, "bob}", "render.view.follow",
                   "'fit' and 'follow' are two camera modes; give one of fit, follow and keys");
  expectStyleError("render:\n  view: {follow: bob, keys: [{t: 0}]}\n", 10, "[{t: 0}]", "render.view.keys",
                   "'follow' and 'keys' are two camera modes");
  expectStyleError("render:\n  view: {keys: [{t: 0}, {t: 1}, {t: 1}]}\n", 10, "1}]}", "render.view.keys[2].t",
                   "expected t > 1 (the key before's): keys are in increasing time, got 1");
  expectStyleError("render:\n  view: {keys: [{t: 2}, {t: 1}]}\n", 10, "1}]}", "render.view.keys[1].t",
                   "expected t > 2");
  expectStyleError("render:\n  view: {keys: []}\n", 10, "[]", "render.view.keys", "expected at least one key");
  expectStyleError("render:\n  view: {keys: [{t: -1}]}\n", 10, "-1", "render.view.keys[0].t", "expected a number ≥ 0");
  expectStyleError("render:\n  view: {keys: [{t: 0, height: 0}]}\n", 10, "0}]}", "render.view.keys[0].height",
                   "expected a number > 0");
  expectStyleError("render:\n  view: {follow: cloth}\n", 10, "cloth}", "render.view.follow", "is a whole grid");
  expectStyleError("render:\n  view: {follow: \"link0@[0.5, 0]\"}\n", 10, "\"link0@", "render.view.follow",
                   "is a point on a rigid body");
  expectStyleError("render:\n  view: {fit: [bob, nobody]}\n", 10, "nobody", "render.view.fit[1]",
                   "nothing is named 'nobody'");
  expectStyleError("render:\n  view: {margin: 0.2}\n", 10, "0.2}", "render.view.margin", "'margin' is the fit mode's");
  expectStyleError("render:\n  view: {fit: all, margin: -0.5}\n", 10, "-0.5}", "render.view.margin",
                   "expected a number ≥ 0, got -0.5");
  expectStyleError("render:\n  view: {follow: bob, smoothing: -1}\n", 10, "-1}", "render.view.smoothing", "≥ 0");
  expectStyleError("render:\n  view: {smoothing: 1}\n", 10, "1}", "render.view.smoothing",
                   "'smoothing' is the follow mode's");
}

TEST_CASE("style: selections and the camera's fit count toward --limit endpoints") {
  SceneLimits limits;
  limits.endpoints = 10;
  const std::string base = "name: t\ngrids: [{name: big, size: [5, 5]}]\n";
  // The fit's 5 points, then each selection's 5: refused at the entry that passes 10, with the option
  // that raises the limit.
  const StyleRefusal r =
      styleRefusalOf(base +
                         "style:\n  select:\n    - {particles: \"big[*][0]\"}\n    - {particles: \"big[0][*]\"}\n"
                         "render: {view: {fit: [\"big[1][*]\"]}}\n",
                     {}, nullptr, limits);
  CHECK(r.keyPath == "style.select[1].particles");
  CHECK(r.message.find("this makes 15 points named by references") != std::string::npos);
  CHECK(r.message.find("--limit endpoints=N") != std::string::npos);
  const StyleRefusal fit = styleRefusalOf(base + "render: {view: {fit: big}}\n", {}, nullptr, limits);
  CHECK(fit.keyPath == "render.view.fit");
  CHECK(fit.message.find("this makes 25 points") != std::string::npos);
  CHECK_NOTHROW(loadScenarioText(base + "render: {view: {fit: all}}\n", "s.yaml", {}, limits));
}

TEST_CASE("style: --set style.… sets any key, and a bad value names the option") {
  const std::string yaml = "style:\n  select:\n    - {particles: bob, label: before}\n";
  const Scenario s =
      loadedStyled(yaml, {parseOverride("style.particles.color_by=speed"), parseOverride("style.select[0].label=x"),
                          parseOverride("render.view.follow=link1")});
  CHECK(s.style.particles.colorBy == style::ParticleQuantity::speed);
  REQUIRE(s.style.select.size() == 1);
  CHECK(s.style.select[0].label == "x");
  CHECK(s.render.view.followBody == 1);

  const StyleRefusal r = styleRefusalOf(kStyleBase + yaml, {parseOverride("style.particles.color_by=speeed")});
  CHECK(r.file == "s.yaml");
  CHECK(r.line == 0);
  CHECK(r.keyPath == "style.particles.color_by");
  CHECK(r.origin == "--set style.particles.color_by=speeed");
  CHECK(r.message.find("did you mean 'speed'?") != std::string::npos);
}

TEST_CASE("style: a style file is merged over the scenario's section before validation") {
  const std::string yaml =
      "style:\n"
      "  particles: {color_by: speed, colormap: magma, radius: 2px}\n"
      "  title: from the scenario\n";
  SUBCASE("the file's keys win; maps merge key by key, keeping the scenario's other keys") {
    const StyleFile file{"particles: {colormap: viridis_r}\ntitle: from the style file\nscale_bar: true\n",
                         "look.yaml"};
    const Scenario s = loadedStyled(yaml, {}, &file);
    CHECK(s.style.particles.colorBy == style::ParticleQuantity::speed);  // the scenario's sibling
    CHECK(s.style.particles.radius == style::Length{2.0, true});
    CHECK(s.style.particles.colormap == style::Colormap{style::ColormapName::viridis, true});
    CHECK(s.style.title == "from the style file");
    CHECK(s.style.scaleBar);
  }
  SUBCASE("lists are replaced, not merged; null clears a key") {
    const StyleFile file{"particles: {color_by: ~, color: red}\nselect: [{bodies: link0}]\n", "look.yaml"};
    const Scenario s = loadedStyled(yaml + "  select: [{particles: bob}, {particles: cloth}]\n", {}, &file);
    CHECK_FALSE(s.style.particles.colorBy);
    CHECK(s.style.particles.color == style::Color{255, 0, 0, 255});
    REQUIRE(s.style.select.size() == 1);
    CHECK(s.style.select[0].bodies == indices({0}));
  }
  SUBCASE("a scenario without a style takes the file's whole") {
    const StyleFile file{"particles: {color_by: height}\n", "look.yaml"};
    CHECK(loadedStyled("", {}, &file).style.particles.colorBy == style::ParticleQuantity::height);
  }
  SUBCASE("--set applies after the style file") {
    const StyleFile file{"title: file\n", "look.yaml"};
    CHECK(loadedStyled(yaml, {parseOverride("style.title=set")}, &file).style.title == "set");
  }
  SUBCASE("errors in what the file gave name the file, its line and column") {
    const StyleFile file{"title: fine\nparticles:\n  colormap: virdis\n", "look.yaml"};
    const StyleRefusal r = styleRefusalOf(kStyleBase + yaml, {}, &file);
    CHECK(r.file == "look.yaml");
    CHECK(r.line == 3);
    CHECK(r.column == 13);
    CHECK(r.keyPath == "style.particles.colormap");
    CHECK(r.message.find("did you mean 'viridis'?") != std::string::npos);
    CHECK(r.what.starts_with("look.yaml:3:13: error: style.particles.colormap: unknown colormap"));
    const StyleFile unknownKey{"particles:\n  colr: red\n", "look.yaml"};
    const StyleRefusal key = styleRefusalOf(kStyleBase + yaml, {}, &unknownKey);
    CHECK(key.file == "look.yaml");
    CHECK(key.line == 2);
    CHECK(key.column == 3);
    CHECK(key.message.find("did you mean 'color'?") != std::string::npos);
    const StyleFile whole{"select:\n  - {particles: nobody}\n", "look.yaml"};
    const StyleRefusal ref = styleRefusalOf(kStyleBase, {}, &whole);
    CHECK(ref.file == "look.yaml");
    CHECK(ref.line == 2);
    CHECK(ref.column == 17);
  }
  SUBCASE("errors in what the scenario kept name the scenario") {
    const StyleFile file{"title: fine\n", "look.yaml"};
    const StyleRefusal r = styleRefusalOf(kStyleBase + "style:\n  particles: {colormap: virdis}\n", {}, &file);
    CHECK(r.file == "s.yaml");
    CHECK(r.line == 10);
  }
  SUBCASE("a style file that is not one map of keys") {
    for (const auto& [text, fragment] : std::vector<std::pair<std::string, std::string>>{
             {"", "the file is empty; expected a style"},
             {"- particles\n", "expected a style: a map of the style section's keys"},
             {"title: a\ntitle: b\n", "duplicate key 'title'"},
             {"title: [\n", "YAML syntax error"}}) {
      const StyleFile file{text, "look.yaml"};
      const StyleRefusal r = styleRefusalOf(kStyleBase + yaml, {}, &file);
      CAPTURE(text);
      CHECK(r.file == "look.yaml");
      CHECK_MESSAGE(r.message.find(fragment) != std::string::npos, r.message);
    }
  }
}

TEST_CASE("style: the program's check reports a bad --set style.… with exit 2, the option and a suggestion") {
  particles::test::Scratch s;
  const std::string cloth = (particles::test::kScenarios / "cloth.yaml").string();
  const particles::test::Result r = s.run("check '" + cloth + "' --set style.particles.color_by=speeed");
  CHECK(r.code == 2);
  CHECK_MESSAGE(
      r.err.find("style.particles.color_by (from --set style.particles.color_by=speeed)") != std::string::npos, r.err);
  CHECK_MESSAGE(r.err.find("did you mean 'speed'?") != std::string::npos, r.err);
}

TEST_CASE("style: check and render take --style FILE, whose errors name it, with exit 2") {
  particles::test::Scratch s;
  const std::string cloth = (particles::test::kScenarios / "cloth.yaml").string();
  s.write("look.yaml", "particles: {color_by: speed}\ncolorbar: {for: particles}\n");
  particles::test::Result r = s.run("check '" + cloth + "' --style look.yaml");
  CHECK_MESSAGE(r.code == 0, r.err);
  s.write("bad.yaml", "particles:\n  color_by: sped\n");
  for (const std::string& command : {"check '" + cloth + "'", "render '" + cloth + "' -o frame.png --at 0"}) {
    r = s.run(command + " --style bad.yaml");
    CAPTURE(command);
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("bad.yaml:2:13: error: style.particles.color_by: unknown particle quantity 'sped'") !=
                      std::string::npos,
                  r.err);
  }
  CHECK_FALSE(std::filesystem::exists(s.dir / "frame.png"));
  r = s.run("check '" + cloth + "' --style missing.yaml");
  CHECK(r.code == 2);
  CHECK_MESSAGE(r.err.find("missing.yaml") != std::string::npos, r.err);
}
