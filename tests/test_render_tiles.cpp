// The tile path (render/tile_bins.hpp, render/tile_program.hpp): shapes binned into screen tiles
// on the CPU and drawn by one full-screen pass. Its records against the triangle path's edges, its
// bins against a brute-force search over every pixel, its pixels against the triangle path's on the
// demos, and what `auto` picks.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <utility>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/solver.hpp"
#include "render/frame_mesh.hpp"
#include "render/image_compare.hpp"
#include "render/renderer.hpp"
#include "render/shader_program.hpp"
#include "render/shape_mesh.hpp"
#include "render/tile_bins.hpp"
#include "render_support.hpp"
#include "scenario/scenario.hpp"

using namespace particles;
using namespace particles::render;
using particles::test::DemoFrame;
using particles::test::demoFrame;
using particles::test::rasterOptions;

namespace {

// Whether pixel centre (x + ½, y + ½) lies in the shape grown by the fringe: the pixels the
// triangle path gives a fragment (and the only ones a shape can colour).
bool centreInGrownShape(const ShapeRecord& r, int x, int y) {
  const float cx = float(x) + 0.5f, cy = float(y) + 0.5f;
  if (r.texel[3][1] == kAnnulusKind) {
    const float d = std::hypot(cx - r.texel[0][0], cy - r.texel[0][1]);
    return d <= r.texel[0][2] + kFringePx && d >= r.texel[0][3] - kFringePx;
  }
  const unsigned smooth = unsigned(r.texel[3][1]);
  for (int k = 0; k < 4; ++k) {
    const float d = r.texel[0][k] * cx + r.texel[1][k] * cy + r.texel[2][k];
    if (d < -((smooth >> k & 1u) ? kFringePx : 0.0f)) return false;
  }
  return true;
}

// Whether the shape covers point (x, y) itself (no fringe).
bool covers(const ShapeRecord& r, float x, float y) {
  if (r.texel[3][1] == kAnnulusKind) {
    const float d = std::hypot(x - r.texel[0][0], y - r.texel[0][1]);
    return d <= r.texel[0][2] && d >= r.texel[0][3];
  }
  for (int k = 0; k < 4; ++k) {
    if (r.texel[0][k] * x + r.texel[1][k] * y + r.texel[2][k] < 0.0f) return false;
  }
  return true;
}

// Whether the shape covers every sample of every sample pattern in every pixel of the tile.
bool coversTile(const ShapeRecord& r, const TileBins& bins, int tx, int ty) {
  for (int y = ty * kTileSizePx; y < std::min((ty + 1) * kTileSizePx, bins.height()); ++y) {
    for (int x = tx * kTileSizePx; x < std::min((tx + 1) * kTileSizePx, bins.width()); ++x) {
      for (int samples : kSampleCounts) {
        for (const Vec2& o : samplePattern(samples)) {
          if (!covers(r, float(x + 0.5 + o.x()), float(y + 0.5 + o.y()))) return false;
        }
      }
    }
  }
  return true;
}

// Every (shape, tile) pair where the shape reaches a pixel centre of the tile must be listed, in
// the order the shapes were added, unless it lies behind the tile's first listed shape and that
// one covers the whole tile. Returns how many listed pairs reach no pixel (the bins' slack).
long checkBins(const TileBins& bins) {
  const int tilesX = bins.tilesPerRow(), tilesY = bins.tileRows();
  REQUIRE(bins.tiles().size() == size_t(2 * tilesX * tilesY));
  long slack = 0, hiddenPairs = 0;
  for (int ty = 0; ty < tilesY; ++ty) {
    for (int tx = 0; tx < tilesX; ++tx) {
      const size_t t = size_t(ty * tilesX + tx);
      const std::uint32_t first = bins.tiles()[2 * t], count = bins.tiles()[2 * t + 1];
      std::vector<bool> inList(bins.shapes().size(), false);
      for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t s = bins.items()[first + i];
        if (i > 0) CHECK(s > bins.items()[first + i - 1]);  // painter's order, no repeats
        inList[s] = true;
      }
      for (size_t s = 0; s < bins.shapes().size(); ++s) {
        bool reaches = false;
        for (int y = ty * kTileSizePx; y < std::min((ty + 1) * kTileSizePx, bins.height()) && !reaches; ++y) {
          for (int x = tx * kTileSizePx; x < std::min((tx + 1) * kTileSizePx, bins.width()) && !reaches; ++x) {
            reaches = centreInGrownShape(bins.shapes()[s], x, y);
          }
        }
        if (reaches && !inList[s]) {
          const bool hidden = count > 0 && s < bins.items()[first] &&
                              coversTile(bins.shapes()[bins.items()[first]], bins, tx, ty);
          CHECK_MESSAGE(hidden, "shape ", s, " reaches tile ", tx, ",", ty, " but is not listed");
          if (hidden) ++hiddenPairs;
        }
        if (inList[s] && !reaches) ++slack;
      }
    }
  }
  MESSAGE("pairs left out behind a shape covering the tile: ", hiddenPairs);
  return slack;
}

}  // namespace

TEST_CASE("tile bins: a line's record is the record of its rectangle as a convex shape") {
  TileBins direct, generic;
  direct.reset(64, 64);
  generic.reset(64, 64);
  const render::Rgb col{10, 200, 30};
  const P2 a = {10.3f, 20.7f}, b = {41.9f, 33.1f};
  direct.line(a, b, 3.0f, col, true);
  // What ShapeSink::line builds: the corners a + n, b + n, b − n, a − n of the capped segment.
  const float len = std::hypot(b[0] - a[0], b[1] - a[1]);
  const float dx = (b[0] - a[0]) / len, dy = (b[1] - a[1]) / len, h = 1.5f;
  const P2 a2 = {a[0] - dx * h, a[1] - dy * h}, b2 = {b[0] + dx * h, b[1] + dy * h};
  const float nx = -dy * h, ny = dx * h;
  generic.convex({{a2[0] + nx, a2[1] + ny}, {b2[0] + nx, b2[1] + ny}, {b2[0] - nx, b2[1] - ny}, {a2[0] - nx, a2[1] - ny}},
                 col);
  REQUIRE(direct.shapes().size() == 1);
  REQUIRE(generic.shapes().size() == 1);
  for (int t = 0; t < 4; ++t) {
    for (int k = 0; k < 4; ++k) {
      CHECK(direct.shapes()[0].texel[t][k] == doctest::Approx(generic.shapes()[0].texel[t][k]).epsilon(1e-5));
    }
  }
  CHECK(direct.shapes()[0].texel[3][0] == 10.0f + 256.0f * 200.0f + 65536.0f * 30.0f);  // the colour, exactly
  CHECK(direct.shapes()[0].texel[3][1] == 15.0f);                                     // every edge smoothed
}

TEST_CASE("tile bins: every tile lists, in painter's order, every shape that reaches one of its pixels") {
  TileBins bins;
  bins.reset(203, 157);  // not a multiple of the tile size: the last row and column are partial
  const render::Rgb col{1, 2, 3};
  // Small and large discs and rings (the large ones take the ring test), lines in every direction
  // (long ones take the edge test), a triangle with one shared edge, a huge quad like a half-plane's,
  // and shapes partly or wholly off the image.
  bins.disc({20.5f, 30.25f}, 4.0f, col);
  bins.disc({100.0f, 80.0f}, 45.0f, col);
  bins.ring({60.0f, 70.0f}, 50.0f, 1.5f, col);
  bins.ring({-20.0f, -20.0f}, 3.0f, 1.5f, col);  // off the image
  for (int i = 0; i < 24; ++i) {
    const double angle = 0.27 * i;
    const P2 from = {float(100 + 12 * std::cos(angle)), float(78 + 9 * std::sin(angle))};
    const P2 to = {float(100 + (20 + 7 * i) * std::cos(angle)), float(78 + (15 + 6 * i) * std::sin(angle))};
    bins.line(from, to, 1.5f + 0.2f * float(i % 4), col, i % 2 == 0);
  }
  bins.convex({{150.0f, 20.0f}, {190.0f, 60.0f}, {140.0f, 75.0f}}, col, 0b101);
  bins.convex({{-500.0f, 120.0f}, {700.0f, 110.0f}, {700.0f, 900.0f}, {-500.0f, 900.0f}}, col);
  bins.line({195.0f, 150.0f}, {260.0f, 190.0f}, 2.0f, col);
  bins.disc({100.0f, 80.0f}, 20.0f, col);  // hides what lies behind it, in the tiles it covers whole
  bins.bin();
  const long slack = checkBins(bins);
  MESSAGE("listed pairs reaching no pixel: ", slack, " of ", bins.items().size());
  CHECK(slack < long(bins.items().size()) / 2);  // the edge and ring tests keep the lists tight
  // The last disc's tiles start at it.
  int startingAtDisc = 0;
  for (size_t t = 0; t < bins.tiles().size() / 2; ++t) {
    if (bins.tiles()[2 * t + 1] > 0 && bins.items()[bins.tiles()[2 * t]] == bins.shapes().size() - 1) ++startingAtDisc;
  }
  CHECK(startingAtDisc >= 49);  // a 40 px disc covers at least 7 × 7 tiles of 4 px whole
  // The ring off the image is listed nowhere.
  for (std::uint32_t s : bins.items()) CHECK(s != 3);
}

TEST_CASE("tile bins: the demos' frames bin exactly (every reached tile listed)") {
  for (const auto& [name, at] : {std::pair<std::string, double>{"cloth", 2.5}, {"soft_body", 20.0}, {"rigid_chain", 3.0}}) {
    CAPTURE(name);
    const DemoFrame f = demoFrame(name, at);
    const RenderOptions o = rasterOptions(160, 120, 4, Raster::tiles);
    TileBins bins;
    bins.reset(o.width, o.height);
    buildFrameMesh(f.drawing, f.camera, o, theme(o.themeName), bins);
    bins.bin();
    checkBins(bins);
  }
}

TEST_CASE("tile bins: frameShapeCount makes room for every record of a demo frame at once") {
  // Renderer::render builds the frame into frameShapeCount slots (buildFrameTiles), made at once,
  // so that a large frame's records are not grown by doubling; the sink path adds no more records.
  for (const auto& [name, at] :
       {std::pair<std::string, double>{"cloth", 2.5}, {"soft_body", 20.0}, {"rigid_chain", 3.0}}) {
    CAPTURE(name);
    const DemoFrame f = demoFrame(name, at);
    const RenderOptions o = rasterOptions(160, 120, 4, Raster::tiles);
    const size_t shapes = frameShapeCount(f.drawing);
    TileBins bins, direct;
    bins.reset(o.width, o.height);
    buildFrameTiles(f.drawing, f.camera, o, theme(o.themeName), bins);
    CHECK(bins.shapes().size() == shapes);
    CHECK(bins.shapes().capacity() == shapes);
    direct.reset(o.width, o.height);
    buildFrameMesh(f.drawing, f.camera, o, theme(o.themeName), direct);
    CHECK(direct.shapes().size() <= shapes);
  }
}

TEST_CASE("tile bins: a frame built and binned on threads is the same bytes for every count, and lists the serial path's shapes") {
  // The 150² cloth over the demo's square (spacing 1.92 / 149 m), a disk and a half-plane below it
  // (large shapes covering whole tiles), the mouse pulling: 67,350 shapes, 3 pieces of springs and 2 of particles
  // (render/frame_mesh.cpp), 23 bands of tile rows, and an image whose sides are not whole tiles.
  const DemoFrame f = demoFrame("cloth", 0.05,
                                {scenario::parseOverride("grids.0.size=[150, 150]"),
                                 scenario::parseOverride("grids.0.spacing=[0.012885906040268456, 0.012885906040268456]"),
                                 scenario::parseOverride("simulation.dt=0.001"),
                                 scenario::parseOverride("mouse.0.from=0"),
                                 scenario::parseOverride("colliders=[{type: disk, center: [0.5, -1.2], radius: 0.3}, "
                                                         "{type: half_plane, normal: [0, 1], offset: -1.4}]")});
  const RenderOptions o = rasterOptions(1283, 719, 4, Raster::tiles);
  const render::Palette colors = theme(o.themeName);
  auto build = [&](int threads) {
    WorkerPool pool(threads);
    auto bins = std::make_unique<TileBins>();
    bins->reset(o.width, o.height);
    const size_t recorded = buildFrameTiles(f.drawing, f.camera, o, colors, *bins, threads > 0 ? &pool : nullptr);
    bins->bin(threads > 0 ? &pool : nullptr);
    return std::pair{std::move(bins), recorded};
  };
  const auto [serial, recorded] = build(0);
  REQUIRE(serial->shapes().size() == frameShapeCount(f.drawing));
  REQUIRE(serial->shapes().size() > 60000);
  auto bytes = [](const auto& v) {
    return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v[0]));
  };
  for (int threads : {1, 2, 3, 4}) {
    CAPTURE(threads);
    const auto [bins, count] = build(threads);
    CHECK(count == recorded);
    CHECK(bytes(bins->shapes()) == bytes(serial->shapes()));
    CHECK(bytes(bins->tiles()) == bytes(serial->tiles()));
    CHECK(bytes(bins->items()) == bytes(serial->items()));
    CHECK(bins->runs() == serial->runs());
  }
  // The serial path (TileBins as a sink, degenerate shapes dropped) lists the same records in
  // every tile; there, `recorded` is the number of records.
  TileBins direct;
  direct.reset(o.width, o.height);
  buildFrameMesh(f.drawing, f.camera, o, colors, direct);
  direct.bin();
  CHECK(direct.shapes().size() == recorded);
  REQUIRE(direct.tiles().size() == serial->tiles().size());
  long differing = 0, covered = 0;
  for (size_t t = 0; t < direct.tiles().size() / 2; ++t) {
    const std::uint32_t count = direct.tiles()[2 * t + 1];
    if (count != serial->tiles()[2 * t + 1]) {
      ++differing;
      continue;
    }
    // Below the half-plane's edge (y < −1.4 m: 640.4 px down), the half-plane's fill (shape 0)
    // reaches every tile: a list starting at the disk's fill (shape 2) was cut at its cover.
    const int ty = int(t) / serial->tilesPerRow();
    if (ty * kTileSizePx > 641 && count > 0 && serial->items()[serial->tiles()[2 * t]] == 2) ++covered;
    for (std::uint32_t i = 0; i < count; ++i) {
      const ShapeRecord& a = direct.shapes()[direct.items()[direct.tiles()[2 * t] + i]];
      const ShapeRecord& b = serial->shapes()[serial->items()[serial->tiles()[2 * t] + i]];
      if (std::memcmp(&a, &b, sizeof a) != 0) ++differing;
    }
  }
  CHECK(differing == 0);
  MESSAGE("tiles below the half-plane whose list starts at the disk: ", covered);
  CHECK(covered > 20);
}

TEST_CASE("tile path: the demos' pixels are the triangle path's within the golden tolerance") {
  // Measured at 1280×720 (golden/README.md, "The tile path"): only samples lying exactly on an edge
  // differ by more than 16, which float rounding decides either way in the two paths. At 1 sample
  // per pixel that is whole rows where an edge runs along pixel centres (the cloth's rail: 934 of
  // 921,600 pixels), so 1 sample has its own bound.
  // Away from ties the paths differ only by the 8-bit rounding after each blend, which the tile
  // pass does once at the end: a unit or two.
  particles::test::checkDemoFramesOnPath(Raster::tiles, false, 2, 0.002);
}

TEST_CASE("tile path: the same frame twice is the same bytes, within the golden bound of the triangle path's") {
  // The cloth at 100 × 100: 10,000 particles and 19,800 springs, past kTilesFromShapes (where the
  // GL paths' automatic choice takes the tiles, RenderOptions).
  const DemoFrame large = demoFrame("cloth", 0.5,
                                    {scenario::parseOverride("grids.0.size=[100, 100]"),
                                     scenario::parseOverride(fmt::format("grids.0.spacing=[{0}, {0}]", 1.92 / 99))});
  REQUIRE(large.drawing.particles.size() + large.drawing.springs.size() >= kTilesFromShapes);
  Renderer tiles(rasterOptions(640, 360, 4, Raster::tiles));
  Renderer triangles(rasterOptions(640, 360, 4, Raster::triangles));
  const Image largeTiles = tiles.render(large.drawing, large.camera);
  CHECK(tiles.render(large.drawing, large.camera).rgba == largeTiles.rgba);
  CHECK(tiles.render(large.byIndex, large.camera).rgba == largeTiles.rgba);  // springs by index: the same
  const Image largeTriangles = triangles.render(large.drawing, large.camera);
  CHECK(largeTriangles.rgba != largeTiles.rgba);  // the two paths can be told apart here
  // The rail lies at y = 28.125 px, so both its edges run through a row of samples (27.375 and
  // 28.875): ties, which the triangle path itself decides one way left of its quad's diagonal and
  // the other right of it (Mesa 22.3: 216 pixels over 16, in rows 27 and 28), and Mesa 25.0's
  // framebuffer object (EGL) along the whole of row 27 (416 pixels). Hence the bound: those two rows.
  const ImageComparison c = compareImages(largeTriangles, largeTiles, {16, 2.0 / 360});
  CHECK_MESSAGE(c.passed, c.differing, " pixels differ by more than 16");
  REQUIRE(c.box);
  CHECK(c.box->y0 >= 27);
  CHECK(c.box->y1 <= 28);
  // A small frame between two large ones: nothing left over (the tile pass turns blending off; the
  // triangles turn it on).
  const DemoFrame small = demoFrame("cloth", 0.5);
  Renderer smallTiles(rasterOptions(640, 360, 4, Raster::tiles));
  const Image expectedSmall = smallTiles.render(small.drawing, small.camera);
  CHECK(tiles.render(small.drawing, small.camera).rgba == expectedSmall.rgba);
  CHECK(tiles.render(large.drawing, large.camera).rgba == largeTiles.rgba);
}

TEST_CASE("tile path: an empty frame is the background, and a frame of one odd size draws") {
  Drawing empty;
  Renderer tiles(rasterOptions(37, 23, 4, Raster::tiles));
  const Image& image = tiles.render(empty, Camera{});
  const render::Rgb bg = theme(ThemeName::dark).background;
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    REQUIRE(image.rgba[i] == bg.r);
    REQUIRE(image.rgba[i + 1] == bg.g);
    REQUIRE(image.rgba[i + 2] == bg.b);
    REQUIRE(image.rgba[i + 3] == 255);
  }
  Drawing one;
  one.particles.push_back(Vec2(0.1, -0.2));
  Renderer triangles(rasterOptions(37, 23, 4, Raster::triangles));
  const Image expected = triangles.render(one, Camera{});
  CHECK(tiles.render(one, Camera{}).rgba == expected.rgba);
}
