// The cpu path (render/tile_composite.hpp): the tile path's records composited by the
// program's own threads into the image, without GL. Its pixels against the triangle path's and the
// GL tile pass's on the demos, its rule for a sample exactly on an edge, the same bytes for every
// thread count, frame after frame from one renderer against fresh ones, and what `auto` picks.
#include <doctest/doctest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/worker_pool.hpp"
#include "render/frame_mesh.hpp"
#include "render/image_compare.hpp"
#include "render/renderer.hpp"
#include "render/tile_bins.hpp"
#include "render/tile_composite.hpp"
#include "render_support.hpp"
#include "scenario/scenario.hpp"
#include "skip.hpp"

using namespace particles;
using namespace particles::render;
using particles::test::DemoFrame;
using particles::test::demoFrame;
using particles::test::rasterOptions;

namespace {

// The 150² cloth over the demo's square with a disk and a half-plane below it and the mouse
// pulling (tests/test_render_tiles.cpp's frame built on threads): 67,350 shapes, some covering
// whole tiles.
DemoFrame largeCloth(double at) {
  return demoFrame("cloth", at,
                   {scenario::parseOverride("grids.0.size=[150, 150]"),
                    scenario::parseOverride("grids.0.spacing=[0.012885906040268456, 0.012885906040268456]"),
                    scenario::parseOverride("simulation.dt=0.001"), scenario::parseOverride("mouse.0.from=0"),
                    scenario::parseOverride("colliders=[{type: disk, center: [0.5, -1.2], radius: 0.3}, "
                                            "{type: half_plane, normal: [0, 1], offset: -1.4}]")});
}

// One image drawn by compositeTiles from shapes given to a fresh TileBins.
template <typename AddShapes>
Image composite(int width, int height, int samples, render::Rgb background, AddShapes&& add) {
  TileBins bins;
  bins.reset(width, height);
  add(bins);
  bins.bin();
  CompositedFrame frame;
  frame.image = Image(width, height);
  compositeTiles(bins, samples, background, false, frame);
  return frame.image;
}

std::vector<P2> rectangle(float x0, float y0, float x1, float y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

constexpr render::Rgb kRed{255, 0, 0}, kBlue{0, 0, 255}, kBlack{0, 0, 0};

}  // namespace

TEST_CASE("cpu path: the demos' pixels are the triangle path's within the golden tolerance") {
  // The GL tile pass's records and formulas: it differs from the triangle path where that path's
  // framebuffer rounds after each blend (a unit or two) and at samples lying on an edge, whose
  // side the triangle path's interpolated distances decide by their rounding and the cpu path by
  // GL's top-left rule. Those ties differ by a sample's share. At 16 samples one row of samples
  // lies on the cloth's rail's lower edge (y = 57 px): there the triangle path counts the samples
  // in, the top-left rule out, in 222 pixels of 921,600 by more than 16 (measured), just over the
  // manifest's 0.02 %, and in 2,201 by more than 2 (0.24 %; the tile pass stays under 0.2 %); the golden
  // frames themselves pass at 0.02 % (ctest -L golden).
  particles::test::checkDemoFramesOnPath(Raster::cpu, true, 2, 0.003, 0.0003);
  particles::test::checkDemoFramesOnPath(Raster::cpu, false, 2, 0.003, 0.0003);
}

TEST_CASE("cpu path: the GL tile pass's pixels but for samples on an edge") {
  // The same records and formulas in float; the pass evaluates each sample's distance in two
  // additions (which llvmpipe may fuse) where the cpu path compares with one threshold, and counts
  // every tie in where the cpu path follows the top-left rule. Measured: no pixel differs by more
  // than 1 but where a sample lies on an edge, which the two paths decide differently: the cursor's
  // outline at 4 samples (18 pixels), the rail's lower edge at 16 (1,123 pixels, 222 by a sample's
  // share, over 16).
  for (const auto& [name, at] : {std::pair<std::string, double>{"cloth", 2.5}, {"soft_body", 20.0}, {"rigid_chain", 3.0}}) {
    const DemoFrame f = demoFrame(name, at);
    for (int msaa : kSampleCounts) {
      CAPTURE(name);
      CAPTURE(msaa);
      RenderOptions o;
      o.msaa = msaa;
      o.raster = Raster::tiles;
      Renderer tiles(o);
      o.raster = Raster::cpu;
      Renderer cpu(o);
      const Image expected = tiles.render(f.byIndex, f.camera);
      const Image& actual = cpu.render(f.byIndex, f.camera);
      const ImageComparison close = compareImages(expected, actual, {1, 0.0015});
      CHECK_MESSAGE(close.passed, close.differing, " pixels differ by more than 1");
      const ImageComparison ties = compareImages(expected, actual, {16, 0.0003});
      CHECK_MESSAGE(ties.passed, ties.differing, " pixels differ by more than 16");
    }
  }
}

TEST_CASE("cpu path: a sample on an edge shared by two shapes is covered by one of them, as GL rasterises") {
  // Red in front of blue over black, meeting at x = 10.5 (the centres of column 10) or y = 8.5 (of
  // row 8), at 1 sample per pixel: the centre on the edge belongs to the shape the edge is a left
  // (or top) edge of.
  auto redOverBlue = [](int width, int height, int samples, const std::vector<P2>& blue, const std::vector<P2>& red) {
    return composite(width, height, samples, kBlack, [&](TileBins& bins) {
      bins.convex(blue, kBlue);  // back
      bins.convex(red, kRed);    // front
    });
  };
  const Image redLeft = redOverBlue(32, 16, 1, rectangle(14.5f, 2.0f, 30.0f, 14.0f), rectangle(2.0f, 2.0f, 10.5f, 14.0f));
  CHECK(particles::test::sameRgb(redLeft.pixel(10, 8), kBlack));  // red's right edge; blue starts at 14.5
  CHECK(particles::test::sameRgb(redLeft.pixel(9, 8), kRed));
  const Image redRight = redOverBlue(32, 16, 1, rectangle(2.0f, 2.0f, 10.5f, 14.0f), rectangle(10.5f, 2.0f, 30.0f, 14.0f));
  CHECK(particles::test::sameRgb(redRight.pixel(10, 8), kRed));  // red's left edge
  CHECK(particles::test::sameRgb(redRight.pixel(9, 8), kBlue));
  const Image redBelow = redOverBlue(16, 32, 1, rectangle(2.0f, 2.0f, 14.0f, 8.5f), rectangle(2.0f, 8.5f, 14.0f, 30.0f));
  CHECK(particles::test::sameRgb(redBelow.pixel(8, 8), kRed));  // red's top edge
  const Image redAbove = redOverBlue(16, 32, 1, rectangle(2.0f, 8.5f, 14.0f, 30.0f), rectangle(2.0f, 2.0f, 14.0f, 8.5f));
  CHECK(particles::test::sameRgb(redAbove.pixel(8, 8), kBlue));  // red's bottom edge, blue's top
  CHECK(particles::test::sameRgb(redAbove.pixel(8, 7), kRed));
  // At 4 samples the edge at x = 10.375 runs through a sample of each pixel of column 10 (offsets
  // −0.375, −0.125, 0.125, 0.375): the shape on its right covers 3 samples and the red one on its
  // left 1, never both. Front to back: red's ¼ (rounded to 64/255), then blue's ¾ of what shows.
  const Image shared = redOverBlue(32, 16, 4, rectangle(10.375f, 2.0f, 30.0f, 14.0f), rectangle(2.0f, 2.0f, 10.375f, 14.0f));
  const float red = 64.0f / 255.0f, blue = 191.0f / 255.0f;
  const std::uint8_t* px = shared.pixel(10, 8);
  CHECK(int(px[0]) == int(red * 255.0f + 0.5f));
  CHECK(int(px[2]) == int((1.0f - red) * blue * 255.0f + 0.5f));
}

TEST_CASE("cpu path: the same bytes for every thread count, at every sample count and an odd size") {
  const DemoFrame f = largeCloth(0.05);
  for (int msaa : {1, 4, 16}) {
    CAPTURE(msaa);
    const RenderOptions o = rasterOptions(1283, 719, msaa, Raster::cpu);
    Renderer serial(o);
    const Image expected = serial.render(f.byIndex, f.camera);
    for (int threads : {1, 2, 3, 8}) {
      CAPTURE(threads);
      WorkerPool pool(threads);
      Renderer renderer(o);
      CHECK(renderer.render(f.byIndex, f.camera, &pool).rgba == expected.rgba);
    }
  }
}

TEST_CASE("cpu path: frame after frame from one renderer is what a fresh renderer draws") {
  // A frame rewrites only the tiles with shapes and those that had shapes in the image's previous
  // frame: a moving cloth, an empty frame, and a frame again must each be the whole frame.
  scenario::Scenario s = scenario::loadScenarioFile(test::kScenarios / "cloth.yaml");
  const Camera camera{s.render.viewCenter, s.render.viewHeight};
  for (bool transparent : {false, true}) {
    CAPTURE(transparent);
    RenderOptions o = rasterOptions(320, 240, 4, Raster::cpu);
    o.transparentBackground = transparent;
    Renderer kept(o);
    Stepper stepper(s.system, s.simulation.integrator, s.simulation.dt);
    for (int frame = 0; frame < 8; ++frame) {
      CAPTURE(frame);
      stepper.advanceTo(s.system.time() + 0.25);
      Drawing d;
      s.system.draw(d, SpringDetail::topology);
      if (frame == 4) d = Drawing{};  // nothing: every tile drawn before goes back to the background
      Renderer fresh(o);
      const Image expected = fresh.render(d, camera);
      CHECK(kept.render(d, camera).rgba == expected.rgba);
    }
  }
}

TEST_CASE("cpu path: frames are not read ahead, even where EGL is asked to, and come in order") {
  // The cpu path's frame is whole when drawn: nothing to overlap, so one frame at a time, as on
  // llvmpipe by default, while a GL path with the same request reads ahead.
  if (!glBackendBuilt(GlBackend::egl)) return particles::test::skipTest("this particles has no EGL backend");
  const DemoFrame a = demoFrame("cloth", 0.5), b = demoFrame("cloth", 2.5);
  GlRequest ahead;
  ahead.backend = GlBackend::egl;
  ahead.readBack = GlRequest::ReadBack::ahead;
  RenderOptions o = rasterOptions(320, 240, 4, Raster::cpu);
  Renderer fresh(o);
  const Image first = fresh.render(a.byIndex, a.camera);
  const Image second = fresh.render(b.byIndex, b.camera);
  REQUIRE(first.rgba != second.rgba);
  Renderer renderer(o, ahead);
  CHECK(!renderer.readsAhead());
  CHECK(Renderer(rasterOptions(320, 240, 4, Raster::resident), ahead).readsAhead());
  for (int round = 0; round < 3; ++round) {
    renderer.submit(a.byIndex, a.camera);
    CHECK_THROWS_AS(renderer.submit(b.byIndex, b.camera), std::logic_error);  // one waits already
    CHECK(renderer.collect().rgba == first.rgba);
    renderer.submit(b.byIndex, b.camera);
    CHECK(renderer.collect().rgba == second.rgba);
  }
  CHECK_THROWS_AS(renderer.collect(), std::logic_error);
}

TEST_CASE("cpu path: auto takes it without a GPU, for small and large scenes, and the paths by name stay") {
  const DemoFrame small = demoFrame("cloth", 0.5);
  const DemoFrame large = demoFrame("cloth", 0.5,
                                    {scenario::parseOverride("grids.0.size=[100, 100]"),
                                     scenario::parseOverride(fmt::format("grids.0.spacing=[{0}, {0}]", 1.92 / 99))});
  Renderer automatic(rasterOptions(640, 360, 4, Raster::automatic));
  Renderer cpu(rasterOptions(640, 360, 4, Raster::cpu));
  Renderer resident(rasterOptions(640, 360, 4, Raster::resident));
  const Image smallCpu = cpu.render(small.byIndex, small.camera);
  const Image largeCpu = cpu.render(large.byIndex, large.camera);
  CHECK(resident.render(small.byIndex, small.camera).rgba != smallCpu.rgba);  // the paths can be told apart
  // Small, large, small again from one renderer: nothing left over from the other frame.
  CHECK(automatic.render(small.byIndex, small.camera).rgba == smallCpu.rgba);
  CHECK(automatic.render(large.byIndex, large.camera).rgba == largeCpu.rgba);
  CHECK(automatic.render(small.drawing, small.camera).rgba == smallCpu.rgba);  // springs by position: the same
}

TEST_CASE("compositeTiles: an image of another size and a sample count without a pattern are refused") {
  TileBins bins;
  bins.reset(16, 8);
  bins.bin();
  CompositedFrame frame;
  frame.image = Image(8, 16);
  CHECK_THROWS_WITH_AS(compositeTiles(bins, 4, kBlack, false, frame), "compositeTiles: the image is 8x16, the tiles' frame 16x8",
                       std::invalid_argument);
  frame.image = Image(16, 8);
  CHECK_THROWS_AS(compositeTiles(bins, 3, kBlack, false, frame), std::invalid_argument);
  compositeTiles(bins, 4, render::Rgb{1, 2, 3}, false, frame);
  CHECK(particles::test::sameRgb(frame.image.pixel(15, 7), render::Rgb{1, 2, 3}));
}
