// A frame's look (render/frame_look.hpp) on every raster path: per-particle colours and radii,
// per-spring colours (by position and by index), body fills and outlines, trails and arrows, with
// straight alpha. Exact colours at shape centres, the paths against the triangle path, the same
// bytes for every thread count, an empty look as no look, and lists of the wrong length.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/worker_pool.hpp"
#include "render/errors.hpp"
#include "render/frame_look.hpp"
#include "render/frame_mesh.hpp"
#include "render/gl_backend.hpp"
#include "render/image_compare.hpp"
#include "render/renderer.hpp"
#include "render/shape_mesh.hpp"
#include "render/theme.hpp"
#include "render_support.hpp"
#include "skip.hpp"

using namespace particles;
using namespace particles::render;

namespace {

constexpr int kWidth = 320, kHeight = 240;
// 100 px per world unit, the image's centre at the world's origin.
const Camera kCamera{Vec2(0.0, 0.0), 2.4};

// The world point the camera puts at pixel (x, y) (x right, y down).
Vec2 world(double x, double y) {
  return {(x - 0.5 * kWidth) / 100.0, (0.5 * kHeight - y) / 100.0};
}

RenderOptions lookOptions(Raster raster) {
  RenderOptions o = particles::test::rasterOptions(kWidth, kHeight, 4, raster);
  o.springWidthPx = 4.0;  // wide enough that a spring's middle pixel is covered whole
  return o;
}

// Four particles (the second fixed; the last alone, translucent), a spring by position and two by
// index, a translucent body under a wide trail piece, a trail fading along six pieces and two
// arrows, one of them all head. Shape centres lie on pixel centres, away from other shapes, where
// tests read their colours.
struct StyledFrame {
  Drawing drawing;
  FrameLook look;
};

StyledFrame styledFrame() {
  StyledFrame s;
  Drawing& d = s.drawing;
  d.particles = {world(60.5, 60.5), world(160.5, 60.5), world(110.5, 110.5), world(270.5, 40.5)};
  d.particleFixed = {0, 1, 0, 0};
  Drawing::Spring byPosition;
  byPosition.a = world(60.5, 60.5);
  byPosition.b = world(110.5, 110.5);
  byPosition.strain = 0.0;
  d.springs = {byPosition};
  auto topology = std::make_shared<Drawing::SpringTopology>();
  topology->ends = {0, 1, 1, 2};
  topology->rest = {1.0, 0.7};
  d.springTopology = topology;
  d.bodies = {{world(240.5, 150.5), 0.2, Vec2(0.8, 0.5)}};
  FrameLook& look = s.look;
  look.particleColors = {{220, 40, 40}, {40, 200, 60}, {240, 200, 40}, {30, 60, 230, 128}};
  look.particleRadiiPx = {9.0f, 8.0f, 6.0f, 10.0f};
  look.springColors = {{250, 250, 250}, {255, 128, 0}, {0, 255, 255, 200}};
  look.bodyFills = {{120, 60, 200, 160}};
  look.bodyOutlines = {{255, 255, 255}};
  for (int k = 0; k < 6; ++k) {
    const double x = 20.0 + 20.0 * k;
    const auto alpha = static_cast<unsigned char>(k == 5 ? 255 : 40 * (k + 1));
    look.trails.push_back({world(x, 200.5), world(x + 20.0, 200.5), 6.0f, {100, 220, 255, alpha}});
  }
  // A wide translucent stroke over the middle of the translucent body, which shows through it.
  look.trails.push_back({world(215.0, 150.5), world(265.0, 150.5), 20.0f, {10, 120, 40, 128}});
  look.arrows = {{world(20.0, 150.5), world(120.0, 150.5), 5.0f, {255, 90, 90, 200}},
                 {world(200.0, 215.5), world(208.0, 215.5), 4.0f, {250, 250, 120}}};
  return s;
}

// Whether a GL context can be made here; the GL paths' tests are skipped where none can.
bool glAvailable() {
  static const bool available = [] {
    try {
      probeGl({});
      return true;
    } catch (const RenderError&) {
      return false;
    }
  }();
  return available;
}

Image renderOn(Raster raster, const StyledFrame& s, const FrameLook* look, WorkerPool* pool = nullptr,
               bool transparent = false) {
  RenderOptions o = lookOptions(raster);
  o.transparentBackground = transparent;
  Renderer renderer(o);
  return renderer.render(s.drawing, kCamera, pool, look);
}

// `color` with straight alpha over `background`, as the paths blend a shape covering a pixel whole.
Rgb over(Rgba color, Rgb background) {
  const double a = color.a / 255.0;
  auto channel = [&](int c, int b) { return static_cast<unsigned char>(std::floor(c * a + b * (1.0 - a) + 0.5)); };
  return {channel(color.r, background.r), channel(color.g, background.g), channel(color.b, background.b)};
}

// Checks the pixel at (x, y) against `expected`, each channel within `slack`.
void checkPixel(const Image& image, int x, int y, Rgb expected, int slack, const char* what) {
  const std::uint8_t* p = image.pixel(x, y);
  INFO("shape: ", what);
  CAPTURE(x);
  CAPTURE(y);
  INFO("got ", int(p[0]), ",", int(p[1]), ",", int(p[2]), ", expected ", int(expected.r), ",", int(expected.g), ",",
       int(expected.b), " ± ", slack);
  CHECK(std::abs(int(p[0]) - int(expected.r)) <= slack);
  CHECK(std::abs(int(p[1]) - int(expected.g)) <= slack);
  CHECK(std::abs(int(p[2]) - int(expected.b)) <= slack);
  CHECK(int(p[3]) == 255);
}

// The colours every path must give at the frame's shape centres: exact where the shape is opaque,
// within 1 of the blend where it is not (the triangle path's framebuffer blends in fixed point).
void checkShapeCentres(const Image& image, const StyledFrame& s) {
  const Rgb background = theme(ThemeName::dark).background;
  const FrameLook& look = s.look;
  checkPixel(image, 60, 60, look.particleColors[0].rgb(), 0, "free particle");
  checkPixel(image, 160, 60, look.particleColors[1].rgb(), 0, "fixed particle, a square");
  checkPixel(image, 166, 66, look.particleColors[1].rgb(), 0, "fixed particle's corner, 0.9 of its own radius");
  checkPixel(image, 270, 40, over(look.particleColors[3], background), 1, "translucent particle");
  checkPixel(image, 279, 40, over(look.particleColors[3], background), 1, "translucent particle's own radius");
  checkPixel(image, 85, 85, look.springColors[0].rgb(), 0, "spring by position");
  checkPixel(image, 110, 60, look.springColors[1].rgb(), 0, "spring by index");
  checkPixel(image, 135, 85, over(look.springColors[2], background), 1, "translucent spring by index");
  // The wide trail piece covers whole tiles of the body, and hides it in none: on the tile and cpu
  // paths only an opaque shape starts a tile's list (TileBins::bin).
  const Rgb body = over(look.bodyFills[0], background);
  checkPixel(image, 240, 168, body, 1, "body fill over the background");
  checkPixel(image, 240, 150, over(look.trails[6].color, body), 1, "trail over the body");
  for (int k = 0; k < 6; ++k) {
    checkPixel(image, 30 + 20 * k, 200, over(look.trails[size_t(k)].color, background), 1, "trail piece");
  }
  // The arrow is drawn once over every pixel: along its shaft, where shaft and head meet (x = 105),
  // and in its head.
  for (int x : {70, 104, 105, 110, 114}) checkPixel(image, x, 150, over(look.arrows[0].color, background), 1, "arrow");
  checkPixel(image, 202, 215, look.arrows[1].color.rgb(), 0, "short arrow, all head");
  checkPixel(image, 5, 5, background, 0, "background");
}

}  // namespace

TEST_CASE("frame look: every raster path draws the look's colours, radii, trails and arrows") {
  const StyledFrame s = styledFrame();
  {
    CAPTURE("cpu");
    checkShapeCentres(renderOn(Raster::cpu, s, &s.look), s);
  }
  if (!glAvailable()) return particles::test::skipTest("no GL context can be made here: the GL paths are not checked");
  for (Raster raster : {Raster::triangles, Raster::tiles, Raster::resident}) {
    CAPTURE(rasterNameOf(raster));
    checkShapeCentres(renderOn(raster, s, &s.look), s);
  }
}

TEST_CASE("frame look: the paths agree within the tolerances they keep on the demos") {
  // tests/test_render_tiles.cpp, test_render_cpu.cpp and test_render_resident.cpp: the tile and cpu
  // paths within 2 of the triangle path in all but 0.2 % of the pixels, the resident path within 1
  // in all but 0.02 %; none by more than 16 in over 0.03 %. Translucent shapes add nothing to that:
  // each path rounds the covered share times alpha to 8 bits alike, and the triangle path's
  // framebuffer rounds after each blend where the others round once. Measured (llvmpipe): the cpu
  // and tile paths within 1 of the triangle path (1,771 of 76,800 pixels differ, all by 1), the
  // resident path equal to it; over a transparent background, where unpremultiplying a faint
  // pixel magnifies its rounding, within 3 (1,027 pixels differ, none by more than 16).
  if (!glAvailable()) return particles::test::skipTest("no GL context can be made here: nothing to compare with");
  const StyledFrame s = styledFrame();
  struct Bound {
    Raster raster;
    int rounding;
    double share;
  };
  for (bool transparent : {false, true}) {
    CAPTURE(transparent);
    const Image triangles = renderOn(Raster::triangles, s, &s.look, nullptr, transparent);
    for (const Bound& bound :
         {Bound{Raster::cpu, 2, 0.002}, Bound{Raster::tiles, 2, 0.002}, Bound{Raster::resident, 1, 0.0002}}) {
      CAPTURE(rasterNameOf(bound.raster));
      const Image other = renderOn(bound.raster, s, &s.look, nullptr, transparent);
      const ImageComparison close = compareImages(triangles, other, {bound.rounding, bound.share});
      MESSAGE(rasterNameOf(bound.raster), std::string(transparent ? " (transparent)" : ""), ": largest difference ",
              close.largestDifference, ", ", compareImages(triangles, other, {0, 1.0}).differing, " pixels differ");
      CHECK_MESSAGE(close.passed, close.differing, " pixels differ by more than ", bound.rounding);
      const ImageComparison ties = compareImages(triangles, other, {16, 0.0003});
      CHECK_MESSAGE(ties.passed, ties.differing, " pixels differ by more than 16");
    }
  }
}

TEST_CASE("frame look: the cpu and tile paths give the same bytes on 1, 2 and 3 threads") {
  // A trail of 40,000 pieces: built in three pieces of kShapesPerPiece on threads.
  StyledFrame s = styledFrame();
  for (int i = 0; i < 40000; ++i) {
    const double t = 0.002 * i, next = 0.002 * (i + 1);
    auto spiral = [](double u) { return world(160.0 + 6.0 * u * std::cos(u), 120.0 + 6.0 * u * std::sin(u)); };
    s.look.trails.push_back({spiral(t), spiral(next), 2.5f, {200, 255, 100, static_cast<unsigned char>(i % 256)}});
  }
  std::vector<Raster> rasters = {Raster::cpu};
  if (glAvailable()) rasters.push_back(Raster::tiles);
  for (Raster raster : rasters) {
    CAPTURE(rasterNameOf(raster));
    const Image serial = renderOn(raster, s, &s.look);
    for (int threads : {2, 3}) {
      CAPTURE(threads);
      WorkerPool pool(threads);
      CHECK(renderOn(raster, s, &s.look, &pool).rgba == serial.rgba);
    }
  }
  if (!glAvailable()) particles::test::skipTest("no GL context can be made here: the tile path is not checked");
}

TEST_CASE("frame look: an empty look, or one of the theme's own colours and radius, is no look to the byte") {
  const StyledFrame s = styledFrame();
  const Palette palette = theme(ThemeName::dark);
  FrameLook themed;
  for (char fixed : s.drawing.particleFixed)
    themed.particleColors.push_back(fixed ? palette.fixedParticle : palette.particle);
  themed.particleRadiiPx.assign(s.drawing.particles.size(), particleRadiusPx(kCamera, lookOptions(Raster::cpu)));
  themed.bodyFills = {palette.bodyFill};
  themed.bodyOutlines = {palette.bodyOutline};
  const FrameLook empty;
  std::vector<Raster> rasters = {Raster::cpu};
  if (glAvailable()) rasters.insert(rasters.end(), {Raster::triangles, Raster::tiles, Raster::resident});
  for (Raster raster : rasters) {
    CAPTURE(rasterNameOf(raster));
    const Image plain = renderOn(raster, s, nullptr);
    CHECK(renderOn(raster, s, &empty).rgba == plain.rgba);
    CHECK(renderOn(raster, s, &themed).rgba == plain.rgba);
  }
  if (!glAvailable()) particles::test::skipTest("no GL context can be made here: only the cpu path is checked");
}

TEST_CASE("frame look: a list of neither none nor one per item throws, naming the list") {
  const StyledFrame s = styledFrame();
  const auto wrong = [&](auto change) {
    FrameLook look = s.look;
    change(look);
    return look;
  };
  const std::vector<std::pair<std::string, FrameLook>> cases = {
      {"particleColors", wrong([](FrameLook& l) { l.particleColors.pop_back(); })},
      {"particleRadiiPx", wrong([](FrameLook& l) { l.particleRadiiPx.push_back(3.0f); })},
      {"springColors", wrong([](FrameLook& l) { l.springColors.pop_back(); })},  // one short: by index left out
      {"bodyFills", wrong([](FrameLook& l) { l.bodyFills.push_back(Rgba{}); })},
      {"bodyOutlines", wrong([](FrameLook& l) { l.bodyOutlines.push_back(Rgba{}); })},
  };
  Renderer cpu(lookOptions(Raster::cpu));
  for (const auto& [name, look] : cases) {
    CAPTURE(name);
    ShapeMesh mesh;
    try {
      buildFrameMesh(s.drawing, kCamera, lookOptions(Raster::cpu), theme(ThemeName::dark), mesh, &look);
      FAIL("no exception");
    } catch (const std::invalid_argument& e) {
      CHECK(std::string(e.what()).find("FrameLook::" + name) != std::string::npos);
    }
    CHECK_THROWS_AS(cpu.render(s.drawing, kCamera, nullptr, &look), std::invalid_argument);
  }
}

TEST_CASE("frame look: frameShapeCount counts the trails and arrows, so the tiles' slots are every shape") {
  const StyledFrame s = styledFrame();
  const RenderOptions o = lookOptions(Raster::tiles);
  TileBins bins;
  bins.reset(o.width, o.height);
  buildFrameTiles(s.drawing, kCamera, o, theme(o.themeName), bins, nullptr, &s.look);
  CHECK(bins.shapes().size() == frameShapeCount(s.drawing, &s.look));
  CHECK(frameShapeCount(s.drawing, &s.look) ==
        frameShapeCount(s.drawing) + s.look.trails.size() + 4 * s.look.arrows.size());
}
