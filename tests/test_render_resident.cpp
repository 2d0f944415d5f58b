// The resident path (render/resident_program.hpp): a scene's springs and particles kept
// in GL's buffers, positions sent each frame, particles drawn as instances and springs expanded in
// the vertex shader. System::draw's springs by index against its springs by position; the path's
// pixels against the triangle path's on the demos (on llvmpipe, as CI draws); the topology sent
// once; the same bytes for every thread count; and what a bad topology gets.
#include <doctest/doctest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/worker_pool.hpp"
#include "render/gl_context.hpp"
#include "render/image_compare.hpp"
#include "render/renderer.hpp"
#include "render/resident_program.hpp"
#include "render_support.hpp"
#include "scenario/scenario.hpp"

using namespace particles;
using namespace particles::render;
using particles::test::DemoFrame;
using particles::test::demoFrame;
using particles::test::rasterOptions;

TEST_CASE("System::draw by index: the springs draw() gives by position, as one object for every frame") {
  scenario::Scenario s = scenario::loadScenarioFile(test::kScenarios / "cloth.yaml");
  Stepper(s.system, s.simulation.integrator, s.simulation.dt).advanceTo(0.7);
  const Drawing byPosition = s.system.draw();
  Drawing byIndex;
  s.system.draw(byIndex, SpringDetail::topology);
  REQUIRE(byIndex.springTopology != nullptr);
  CHECK(byIndex.springs.empty());
  const Drawing::SpringTopology& topology = *byIndex.springTopology;
  REQUIRE(topology.rest.size() == byPosition.springs.size());
  REQUIRE(topology.ends.size() == 2 * byPosition.springs.size());
  CHECK(byIndex.particles == byPosition.particles);
  for (size_t i = 0; i < byPosition.springs.size(); ++i) {
    CAPTURE(i);
    const Vec2& a = byIndex.particles[topology.ends[2 * i]];
    const Vec2& b = byIndex.particles[topology.ends[2 * i + 1]];
    REQUIRE(a == byPosition.springs[i].a);
    REQUIRE(b == byPosition.springs[i].b);
    // The strain every path computes from them is System::draw's, bit for bit.
    REQUIRE((a - b).norm() / topology.rest[i] - 1.0 == byPosition.springs[i].strain);
  }
  // Everything else is drawn as before.
  CHECK(byIndex.cursors.size() == byPosition.cursors.size());
  CHECK(byIndex.guideLines.size() == byPosition.guideLines.size());
  // A later frame shares the same topology: a renderer that holds it sends it no more.
  Stepper(s.system, s.simulation.integrator, s.simulation.dt).advanceTo(0.8);
  Drawing later;
  s.system.draw(later, SpringDetail::topology);
  CHECK(later.springTopology == byIndex.springTopology);
  CHECK(later.particles != byIndex.particles);
  // Cleared, a drawing lets go of it.
  later.clear();
  CHECK(later.springTopology == nullptr);
}

TEST_CASE("System::draw by index: springs on bodies stay by position") {
  // The rigid chain's springs join anchors on its links: only positions can show them.
  scenario::Scenario s = scenario::loadScenarioFile(test::kScenarios / "rigid_chain.yaml");
  Drawing d;
  s.system.draw(d, SpringDetail::topology);
  CHECK(d.springTopology == nullptr);
  CHECK(d.springs.size() == s.system.draw().springs.size());
  CHECK(!d.springs.empty());
}

TEST_CASE("resident path: the demos' pixels are the triangle path's within the golden tolerance") {
  // The same coverage shader, fed the same boundaries: the two differ only where a sample lies
  // within float rounding of an edge, as the tile path does (tests/test_render_tiles.cpp), and
  // elsewhere not at all (the same blending in the same framebuffer). The rigid chain's springs
  // come by position, drawn on the CPU between the resident path's particles.
  for (bool byIndex : {true, false}) {  // springs by position: drawn on the CPU between the instances
    CAPTURE(byIndex);
    particles::test::checkDemoFramesOnPath(Raster::resident, byIndex, 1, 0.0002);
  }
}

TEST_CASE("resident path: a transparent background, and the other paths given springs by index") {
  const DemoFrame f = demoFrame("cloth", 1.5);
  RenderOptions o = rasterOptions(640, 360, 4, Raster::triangles);
  o.transparentBackground = true;
  Renderer triangles(o);
  o.raster = Raster::resident;
  Renderer resident(o);
  const Image expected = triangles.render(f.drawing, f.camera);
  const ImageComparison c = compareImages(expected, resident.render(f.byIndex, f.camera), {1, 0.0002});
  CHECK_MESSAGE(c.passed, c.differing, " pixels differ by more than 1");
  // The triangle and tile paths build springs by index as they build them by position: the same
  // bytes.
  CHECK(triangles.render(f.byIndex, f.camera).rgba == expected.rgba);
  o.raster = Raster::tiles;
  Renderer tiles(o);
  const Image tiled = tiles.render(f.drawing, f.camera);
  CHECK(tiles.render(f.byIndex, f.camera).rgba == tiled.rgba);
}

TEST_CASE("resident path: frame after frame from one renderer, each the frame a fresh renderer draws") {
  // The topology stays in GL; the positions and the fixed flags of each frame must not.
  scenario::Scenario s = scenario::loadScenarioFile(test::kScenarios / "cloth.yaml");
  const Camera camera{s.render.viewCenter, s.render.viewHeight};
  const RenderOptions o = rasterOptions(320, 240, 4, Raster::resident);
  Renderer kept(o);
  Stepper stepper(s.system, s.simulation.integrator, s.simulation.dt);
  Drawing d;
  for (double t : {0.5, 1.0, 1.5}) {
    CAPTURE(t);
    stepper.advanceTo(t);
    s.system.draw(d, SpringDetail::topology);
    if (t == 1.5) d.particleFixed.assign(d.particleFixed.size(), 0);  // pins released: drawn as discs
    const Image drawn = kept.render(d, camera);
    Renderer fresh(o);
    CHECK(fresh.render(d, camera).rgba == drawn.rgba);
  }
}

TEST_CASE("resident path: the topology goes to GL once, the positions every frame") {
  const std::unique_ptr<GlContext> context = makeGlContext({}, 64, 64);
  ResidentProgram program(context->gl(), 4, 64, 64, context->flipsY());
  auto topology = std::make_shared<Drawing::SpringTopology>();
  topology->ends = {0, 1, 1, 2};
  topology->rest = {1.0, 1.0};
  const std::vector<float> pixels = {10, 10, 30, 10, 30, 40};
  const std::vector<char> fixed = {1, 0, 0};
  program.upload(pixels, fixed, topology);
  program.upload(pixels, fixed, topology);
  CHECK(program.topologyUploads() == 1);
  program.upload(pixels, fixed, std::make_shared<Drawing::SpringTopology>(*topology));  // another scene's
  CHECK(program.topologyUploads() == 2);
  program.upload(pixels, fixed, nullptr);  // a scene without springs by index
  CHECK(program.topologyUploads() == 2);
  // A spring to a particle the frame lacks is refused, not drawn from whatever GL holds there.
  CHECK_THROWS_AS(program.upload(std::vector<float>{10, 10, 30, 10}, fixed, topology), std::invalid_argument);
}

TEST_CASE("resident path: the same bytes for every thread count, and a bad topology refused") {
  const DemoFrame f = demoFrame("cloth", 2.0, {scenario::parseOverride("grids.0.size=[60, 60]"),
                                               scenario::parseOverride(fmt::format("grids.0.spacing=[{0}, {0}]", 1.92 / 59))});
  Renderer resident(rasterOptions(640, 360, 4, Raster::resident));
  const Image serial = resident.render(f.byIndex, f.camera);
  for (int threads : {1, 2, 3}) {
    CAPTURE(threads);
    WorkerPool pool(threads);
    CHECK(resident.render(f.byIndex, f.camera, &pool).rgba == serial.rgba);
  }
  Drawing bad = f.byIndex;
  auto topology = std::make_shared<Drawing::SpringTopology>(*bad.springTopology);
  topology->ends.back() = std::uint32_t(bad.particles.size());
  bad.springTopology = topology;
  for (Raster raster : {Raster::resident, Raster::triangles, Raster::tiles}) {
    CAPTURE(rasterNameOf(raster));
    Renderer renderer(rasterOptions(160, 120, 4, raster));
    CHECK_THROWS_WITH_AS(renderer.render(bad, f.camera), doctest::Contains("ends at particle"), std::invalid_argument);
    CHECK(renderer.render(f.byIndex, f.camera).width == 160);  // and the renderer draws on
  }
}
