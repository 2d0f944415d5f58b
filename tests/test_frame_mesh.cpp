// The frame's triangles (render/frame_mesh.hpp) checked by numbers, without a GL context: where
// the camera puts shapes, the strain colour of springs, how far guide lines reach, and the order
// shapes are drawn in.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/drawing.hpp"
#include "render/frame_mesh.hpp"
#include "render/render_options.hpp"
#include "render/shape_mesh.hpp"
#include "render/theme.hpp"
#include "render_support.hpp"

using namespace particles;
using namespace particles::render;
using particles::test::projectToPixel;
using particles::test::smallRenderOptions;

namespace {

// Off-centre, so that a frame drawn shifted, flipped or at the wrong scale puts shapes elsewhere.
const Camera kCamera{Vec2(0.25, -0.1), 2.4};

ShapeMesh meshOf(const Drawing& frame, const RenderOptions& options = smallRenderOptions(),
                 const Camera& camera = kCamera, const Palette& colors = theme(ThemeName::dark)) {
  ShapeMesh mesh;
  buildFrameMesh(frame, camera, options, colors, mesh);
  return mesh;
}

Rgb colorOf(const ShapeVertex& v) {
  return {v.rgba[0], v.rgba[1], v.rgba[2]};
}

std::string text(Rgb c) {
  return std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b);
}

// The smallest axis-aligned box around the vertices: a shape's true outline grown by kFringePx
// where it is anti-aliased.
struct Bounds {
  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  float centerX() const { return 0.5f * (x0 + x1); }
  float centerY() const { return 0.5f * (y0 + y1); }
};
Bounds boundsOf(const std::vector<ShapeVertex>& vertices) {
  Bounds b;
  for (const ShapeVertex& v : vertices) {
    b.x0 = std::min(b.x0, v.x), b.x1 = std::max(b.x1, v.x);
    b.y0 = std::min(b.y0, v.y), b.y1 = std::max(b.y1, v.y);
  }
  return b;
}

// A circle vertex (kind 1) knows its offset from the centre: every vertex of a disc points back at
// the same centre.
Vec2 circleCenterOf(const ShapeVertex& v) {
  return {double(v.x) - v.shape[0], double(v.y) - v.shape[1]};
}

}  // namespace

TEST_CASE("frame mesh: a particle is a disc centred where the camera projects it") {
  const System system = particles::test::fallingParticles();
  const Drawing frame = system.draw();
  RenderOptions options = smallRenderOptions();
  const ShapeMesh mesh = meshOf(frame, options);
  REQUIRE_FALSE(mesh.vertices().empty());

  // Vertices in particle order, each disc a run of circle vertices around its own centre.
  struct Disc {
    Vec2 center;
    float outer, inner;
    Rgb color;
  };
  std::vector<Disc> discs;
  for (const ShapeVertex& v : mesh.vertices()) {
    REQUIRE(v.kind == 1.0f);
    const Vec2 c = circleCenterOf(v);
    if (discs.empty() || (c - discs.back().center).norm() > 1e-3)
      discs.push_back({c, v.shape[2], v.shape[3], colorOf(v)});
  }
  REQUIRE(discs.size() == frame.particles.size());
  for (size_t i = 0; i < discs.size(); ++i) {
    const Vec2 expected = projectToPixel(frame.particles[i], kCamera, options.width, options.height);
    INFO("particle " << i << ": disc at " << discs[i].center.transpose() << ", projected " << expected.transpose());
    CHECK((discs[i].center - expected).norm() < 1e-3);
    CHECK(discs[i].outer == doctest::Approx(6.0));  // the radius in pixels
    CHECK(discs[i].inner == 0.0f);                  // a disc, no hole
    CHECK(text(discs[i].color) == text(theme(ThemeName::dark).particle));
  }

  // A radius in world units scales with the camera: 0.05 · 240 px / 2.4 = 5 px.
  options.particleRadius = {0.05, Length::Unit::world};
  CHECK(meshOf(frame, options).vertices().front().shape[2] == doctest::Approx(5.0));
}

TEST_CASE("frame mesh: a fixed particle is a square of 1.8 radii around its projected centre") {
  Drawing frame;
  frame.particles = {Vec2(-0.4, 0.3)};
  frame.particleFixed = {1};
  const RenderOptions options = smallRenderOptions();
  const ShapeMesh mesh = meshOf(frame, options);
  REQUIRE(mesh.vertices().size() == 6);  // one quad
  CHECK(text(colorOf(mesh.vertices()[0])) == text(theme(ThemeName::dark).fixedParticle));
  const Vec2 c = projectToPixel(frame.particles[0], kCamera, options.width, options.height);
  const Bounds b = boundsOf(mesh.vertices());
  const double half = 0.9 * 6.0 + kFringePx;
  CHECK(b.x0 == doctest::Approx(c.x() - half));
  CHECK(b.x1 == doctest::Approx(c.x() + half));
  CHECK(b.y0 == doctest::Approx(c.y() - half));
  CHECK(b.y1 == doctest::Approx(c.y() + half));
}

TEST_CASE("frame mesh: a spring's colour follows its strain") {
  const Palette colors = theme(ThemeName::dark);
  RenderOptions options = smallRenderOptions();
  options.strainForFullColor = 0.2;
  auto colorAt = [&](double strain) {
    Drawing frame;
    frame.springs = {{Vec2(-0.5, 0.1), Vec2(0.5, 0.1), strain}};
    const ShapeMesh mesh = meshOf(frame, options);
    REQUIRE(mesh.vertices().size() == 6);  // one quad, all of one colour
    for (const ShapeVertex& v : mesh.vertices()) REQUIRE(text(colorOf(v)) == text(colorOf(mesh.vertices()[0])));
    return text(colorOf(mesh.vertices()[0]));
  };
  CHECK(colorAt(0.0) == text(colors.springRest));
  CHECK(colorAt(0.2) == text(colors.springStretched));  // full colour at strainForFullColor
  CHECK(colorAt(0.7) == text(colors.springStretched));  // and beyond
  CHECK(colorAt(-0.2) == text(colors.springCompressed));
  CHECK(colorAt(-0.5) == text(colors.springCompressed));
  // Half way: each channel half way from the rest colour, rounded.
  auto halfWay = [](Rgb a, Rgb b) {
    auto m = [](int x, int y) { return static_cast<unsigned char>(std::lround(0.5 * (x + y))); };
    return Rgb{m(a.r, b.r), m(a.g, b.g), m(a.b, b.b)};
  };
  CHECK(colorAt(0.1) == text(halfWay(colors.springRest, colors.springStretched)));
  CHECK(colorAt(-0.1) == text(halfWay(colors.springRest, colors.springCompressed)));
  // The option sets the scale: at 0.4 for full colour, a strain of 0.2 is half way.
  options.strainForFullColor = 0.4;
  CHECK(colorAt(0.2) == text(halfWay(colors.springRest, colors.springStretched)));
  // The same rule as springColor, which the theme offers for legends.
  CHECK(colorAt(0.05) == text(springColor(colors, 0.05, 0.4)));
}

TEST_CASE("theme: mix rounds each channel as std::lround does, halves away from zero") {
  // Every pair of channel values against fractions that land on exact halves, just either side of
  // them, and on whole levels; plus every t in steps of 1/1024.
  std::vector<double> fractions = {0.0, 1.0, 0.5, 0.25, 0.75, 1.0 / 3.0, 2.0 / 3.0};
  for (int k = 1; k < 1024; ++k) fractions.push_back(double(k) / 1024.0);
  for (int level = 1; level < 255; ++level) {
    const double half = (double(level) - 0.5) / 255.0;  // x = 0, y = 255: a level's lower half
    fractions.insert(fractions.end(), {half, std::nextafter(half, 0.0), std::nextafter(half, 1.0)});
  }
  long checked = 0, halves = 0;
  for (int x = 0; x < 256; x += 7) {
    for (int y = 0; y < 256; y += 5) {
      for (double t : fractions) {
        const double exact = double(x) + (double(y) - double(x)) * t;
        const auto expected = static_cast<unsigned char>(std::lround(exact));
        const Rgb got = mix(Rgb{static_cast<unsigned char>(x), 0, 0}, Rgb{static_cast<unsigned char>(y), 0, 0}, t);
        if (got.r != expected)
          FAIL("mix(" << x << ", " << y << ", " << t << ") = " << int(got.r) << ", std::lround gives "
                      << int(expected));
        ++checked;
        if (exact - std::floor(exact) == 0.5) ++halves;
      }
    }
  }
  CHECK(checked > 1'000'000);
  CHECK(halves > 1000);  // the halves themselves were tried, not only values near them
  // The channels are independent.
  CHECK(mix(Rgb{0, 100, 255}, Rgb{255, 0, 0}, 0.5) == Rgb{128, 50, 128});
}

namespace {

// A 2 px guide line through world (0.3, 0.4): the box around its quad, and where the camera puts
// that point.
struct GuideLine {
  Bounds box;
  Vec2 point;  // pixels
};
GuideLine guideLine(Vec2 direction) {
  Drawing frame;
  frame.guideLines = {{Vec2(0.3, 0.4), direction}};
  RenderOptions options = smallRenderOptions();
  options.guideWidthPx = 2.0;
  const ShapeMesh mesh = meshOf(frame, options);
  REQUIRE(mesh.vertices().size() == 6);  // one quad
  CHECK(text(colorOf(mesh.vertices()[0])) == text(theme(ThemeName::dark).guide));
  return {boundsOf(mesh.vertices()), projectToPixel(Vec2(0.3, 0.4), kCamera, options.width, options.height)};
}

}  // namespace

TEST_CASE("frame mesh: a horizontal guide line spans the image and 8 px beyond, at the projected height") {
  const GuideLine line = guideLine(Vec2(1, 0));
  CHECK(line.box.x0 == doctest::Approx(-8.0 - kFringePx));
  CHECK(line.box.x1 == doctest::Approx(320 + 8.0 + kFringePx));
  CHECK(line.box.centerY() == doctest::Approx(line.point.y()));
  CHECK(line.box.y1 - line.box.y0 == doctest::Approx(2.0 + 2 * kFringePx));  // the line's width
}

TEST_CASE("frame mesh: a vertical guide line spans the image and 8 px beyond, at the projected x") {
  const GuideLine line = guideLine(Vec2(0, 1));
  CHECK(line.box.y0 == doctest::Approx(-8.0 - kFringePx));
  CHECK(line.box.y1 == doctest::Approx(240 + 8.0 + kFringePx));
  CHECK(line.box.centerX() == doctest::Approx(line.point.x()));
  CHECK(line.box.x1 - line.box.x0 == doctest::Approx(2.0 + 2 * kFringePx));
}

TEST_CASE("frame mesh: a slanted guide line passes through its point with its slope") {
  // The box around a line's quad is centred on the middle of the drawn segment, which lies on the
  // line: half way across the image for a mostly horizontal line, half way down for a mostly
  // vertical one. World y up is pixel y down, so the pixel slope has the opposite sign.
  SUBCASE("mostly horizontal, rising to the right") {
    const GuideLine line = guideLine(Vec2(1, 0.2).normalized());
    CHECK(line.box.centerX() == doctest::Approx(160.0));
    CHECK(line.box.centerY() == doctest::Approx(line.point.y() - 0.2 * (160.0 - line.point.x())));
  }
  SUBCASE("mostly vertical, leaning to the right") {
    const GuideLine line = guideLine(Vec2(0.3, 1).normalized());
    CHECK(line.box.centerY() == doctest::Approx(120.0));
    CHECK(line.box.centerX() == doctest::Approx(line.point.x() - 0.3 * (120.0 - line.point.y())));
  }
}

TEST_CASE("frame mesh: shapes are drawn back to front in the documented order") {
  // One shape of every list, and a theme in which every role has its own colour, so that each run
  // of vertices names what drew it. Circles (kind 1) and edge shapes (kind 0) of one colour are
  // told apart by their kind.
  Palette colors{};
  const std::vector<std::pair<std::string, Rgb*>> roles = {{"background", &colors.background},
                                                           {"particle", &colors.particle},
                                                           {"fixedParticle", &colors.fixedParticle},
                                                           {"springCompressed", &colors.springCompressed},
                                                           {"springRest", &colors.springRest},
                                                           {"springStretched", &colors.springStretched},
                                                           {"rod", &colors.rod},
                                                           {"guide", &colors.guide},
                                                           {"bodyFill", &colors.bodyFill},
                                                           {"bodyOutline", &colors.bodyOutline},
                                                           {"colliderFill", &colors.colliderFill},
                                                           {"colliderOutline", &colors.colliderOutline},
                                                           {"mouse", &colors.mouse},
                                                           {"mouseOutline", &colors.mouseOutline}};
  for (size_t i = 0; i < roles.size(); ++i) *roles[i].second = Rgb{static_cast<unsigned char>(10 * (i + 1)), 7, 9};
  auto roleOf = [&](const ShapeVertex& v) {
    for (const auto& [name, color] : roles) {
      if (colorOf(v) == *color) return name + (v.kind > 0.5f ? " circle" : "");
    }
    return "unknown " + text(colorOf(v));
  };

  Drawing f;
  f.halfPlanes = {{Vec2(0, 1), -0.8}};
  f.disks = {{Vec2(-0.8, 0.5), 0.2}};
  f.guideCircles = {{Vec2(0, 0.3), 0.3}};
  f.guideLines = {{Vec2(0, 0.8), Vec2(1, 0)}};
  f.springs = {{Vec2(-0.5, 0.2), Vec2(0.5, 0.2), 0.0}};
  f.rods = {{Vec2(-0.5, -0.3), Vec2(0.5, -0.3)}};
  f.bodies = {{Vec2(0.8, 0.5), 0.3, Vec2(0.4, 0.2)}};
  f.particles = {Vec2(0.1, 0.1), Vec2(-0.1, 0.1)};
  f.particleFixed = {0, 1};
  f.cursors = {{Vec2(0.0, -0.55), Vec2(-0.9, -0.55)}};
  const ShapeMesh mesh = meshOf(f, smallRenderOptions(), kCamera, colors);

  std::vector<std::string> drawn;
  for (const ShapeVertex& v : mesh.vertices()) {
    const std::string role = roleOf(v);
    if (drawn.empty() || drawn.back() != role) drawn.push_back(role);
  }
  auto joined = [](const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) out += (out.empty() ? "" : " → ") + name;
    return out;
  };
  const std::vector<std::string> expected = {"colliderFill",
                                             "colliderOutline",  // the half-plane, then its boundary
                                             "colliderFill circle",
                                             "colliderOutline circle",  // the disk, then its rim
                                             "guide circle",
                                             "guide",  // wire, then rail
                                             "springRest",
                                             "rod",  //
                                             "bodyFill",
                                             "bodyOutline",  //
                                             "particle circle",
                                             "fixedParticle",  // in particle order
                                             "mouse",
                                             "mouseOutline"};  // line and arrow, then the arrow's outline
  CHECK(joined(drawn) == joined(expected));
}

TEST_CASE("frame mesh: an empty drawing is no triangles, and the mesh is replaced, not added to") {
  ShapeMesh mesh;
  Drawing frame;
  frame.particles = {Vec2(0, 0)};
  frame.particleFixed = {0};
  buildFrameMesh(frame, kCamera, smallRenderOptions(), theme(ThemeName::dark), mesh);
  const size_t once = mesh.vertices().size();
  REQUIRE(once > 0);
  buildFrameMesh(frame, kCamera, smallRenderOptions(), theme(ThemeName::dark), mesh);
  CHECK(mesh.vertices().size() == once);
  buildFrameMesh(Drawing{}, kCamera, smallRenderOptions(), theme(ThemeName::dark), mesh);
  CHECK(mesh.vertices().empty());
  CHECK_THROWS_AS(buildFrameMesh(frame, Camera{Vec2::Zero(), 0.0}, smallRenderOptions(), theme(ThemeName::dark), mesh),
                  std::invalid_argument);
}

TEST_CASE("frame mesh: frameShapeCount is the number of shapes built, for every kind of drawing item") {
  // Counts what the builder hands a sink; TileBins drops off-screen shapes, this does not.
  struct CountingSink final : ShapeSink {
    size_t shapes = 0;
    void clear() override { shapes = 0; }
    void convex(std::span<const P2>, Rgba, unsigned) override { ++shapes; }
    void line(P2, P2, float, Rgba, bool) override { ++shapes; }
    void annulus(P2, float, float, Rgba) override { ++shapes; }
  };
  Drawing f;
  CountingSink sink;
  auto built = [&] {
    buildFrameMesh(f, kCamera, smallRenderOptions(), theme(ThemeName::dark), sink);
    return sink.shapes;
  };
  CHECK(frameShapeCount(f) == 0);
  CHECK(built() == 0);
  // Each kind on its own, then twice over, so that a wrong count per item shows.
  for (int copies = 1; copies <= 2; ++copies) {
    CAPTURE(copies);
    f = Drawing{};
    for (int i = 0; i < copies; ++i) {
      f.halfPlanes.push_back({Vec2(0, 1), -0.8});
      f.disks.push_back({Vec2(-0.8, 0.5), 0.2});
      f.guideCircles.push_back({Vec2(0, 0.3), 0.3});
      f.guideLines.push_back({Vec2(0, 0.8), Vec2(1, 0)});
      f.springs.push_back({Vec2(-0.5, 0.2), Vec2(0.5, 0.2), 0.0});
      f.rods.push_back({Vec2(-0.5, -0.3), Vec2(0.5, -0.3)});
      f.bodies.push_back({Vec2(0.8, 0.5), 0.3, Vec2(0.4, 0.2)});
      f.particles.push_back(Vec2(0.1, 0.1));
      f.particles.push_back(Vec2(-0.1, 0.1));
      f.particleFixed = std::vector<char>(f.particles.size(), 0);
      f.particleFixed.back() = 1;
      f.cursors.push_back({Vec2(0.0, -0.55), Vec2(-0.9, -0.55)});
    }
    CHECK(frameShapeCount(f) == built());
    const Drawing all = f;
    auto only = [&](auto member) {
      f = Drawing{};
      f.*member = all.*member;
      f.particleFixed = std::vector<char>(f.particles.size(), 1);  // squares: one shape each, as discs
      CHECK(frameShapeCount(f) == built());
    };
    only(&Drawing::halfPlanes);
    only(&Drawing::disks);
    only(&Drawing::guideCircles);
    only(&Drawing::guideLines);
    only(&Drawing::springs);
    only(&Drawing::rods);
    only(&Drawing::bodies);
    only(&Drawing::particles);
    only(&Drawing::cursors);
  }
}
