// Render-only throughput (no encoding): frames per second drawing the three demos at 1280×720
// through the renderer's default GL backend (PARTICLES_GL=egl or osmesa picks one, as for
// `particles render`; the label names it), with 1 (off), 4 (the default) and 16 anti-aliasing
// samples per pixel. Each iteration draws one frame of a state prepared beforehand (the scenario
// advanced to a representative time), so simulation is outside the clock; System::draw() is called
// inside it, as `particles render` does per frame.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "core/drawing.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"
#include "core/worker_pool.hpp"
#include "render/frame_mesh.hpp"
#include "render/renderer.hpp"
#include "render/tile_bins.hpp"
#include "render/tile_composite.hpp"
#include "scenario/scenario.hpp"

namespace {

using namespace particles;

render::GlRequest glRequestFromEnvironment() {
  const char* name = std::getenv("PARTICLES_GL");
  const auto backend = name ? render::glBackendFromName(name) : std::nullopt;
  return {backend.value_or(render::GlBackend::automatic)};
}

void BM_Render(benchmark::State& state, const std::string& file, double at) {
  scenario::Scenario s = scenario::loadScenarioFile(std::string(PARTICLES_SOURCE_DIR) + "/scenarios/" + file);
  Stepper(s.system, s.simulation.integrator, s.simulation.dt).advanceTo(at);
  render::RenderOptions options;
  options.width = 1280;
  options.height = 720;
  options.msaa = int(state.range(0));
  render::Renderer renderer(options, glRequestFromEnvironment());
  state.SetLabel(std::string(render::glBackendName(renderer.gl().backend)));
  const render::Camera camera{s.render.viewCenter, s.render.viewHeight};
  for (auto _ : state) {
    const render::Image& image = renderer.render(s.system.draw(), camera);
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["msaa"] = double(options.msaa);
}

// The cloth demo at n × n particles (its springs, 2n(n − 1), grow with it) over the same 1.92 m
// square, so larger grids are denser in the same frame: 25 (625 particles, the demo), 100 (10,000)
// and 316 (99,856, the large scene), drawn at 1 s, 4 samples, 1280×720, through each raster
// path (render/render_options.hpp), each frame's shapes built (and on the cpu path composited) on a
// pool of one thread per CPU, as `particles render` does. The counters give the cost per primitive
// the renderer draws (particles, springs, guides and the cursor).
void BM_RenderLargeCloth(benchmark::State& state) {
  const int n = int(state.range(0));
  const std::vector<scenario::Override> overrides = {
      scenario::parseOverride(fmt::format("grids.0.size=[{0}, {0}]", n)),
      scenario::parseOverride(fmt::format("grids.0.spacing=[{0}, {0}]", 1.92 / double(n - 1))),
      scenario::parseOverride(fmt::format("mouse.0.grab=cloth[{}][{}]", n - 1, n / 2))};  // bottom middle
  scenario::Scenario s =
      scenario::loadScenarioFile(std::string(PARTICLES_SOURCE_DIR) + "/scenarios/cloth.yaml", overrides);
  Stepper(s.system, s.simulation.integrator, s.simulation.dt).advanceTo(1.0);
  render::RenderOptions options;
  options.width = 1280;
  options.height = 720;
  options.msaa = 4;
  options.raster = render::Raster(state.range(1));
  render::Renderer renderer(options, glRequestFromEnvironment());
  state.SetLabel(std::string(render::glBackendName(renderer.gl().backend)) + " " +
                 std::string(render::rasterNameOf(options.raster)));
  const render::Camera camera{s.render.viewCenter, s.render.viewHeight};
  const Drawing first = s.system.draw();
  const double primitives = double(first.particles.size() + first.springs.size() + first.rods.size() +
                                   first.guideLines.size() + first.guideCircles.size() + first.cursors.size() +
                                   first.halfPlanes.size() + first.disks.size() + first.bodies.size());
  Drawing frame;  // reused, with its springs by index, as `particles render` draws it
  WorkerPool pool(int(std::max(1u, std::thread::hardware_concurrency())));
  for (auto _ : state) {
    s.system.draw(frame, SpringDetail::topology);
    const render::Image& image = renderer.render(frame, camera, &pool);
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["primitives"] = primitives;
  state.counters["ns_per_primitive"] =
      benchmark::Counter(double(state.iterations()) * primitives * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Second argument: 1 triangles, 2 tiles, 3 resident, 4 cpu (render::Raster).
BENCHMARK(BM_RenderLargeCloth)
    ->ArgsProduct({{25, 40, 60, 80, 100, 316}, {1, 2, 3, 4}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The 1000² cloth (scenarios/cloth_million.yaml) stepped 0.01 s on `threads` threads, so that its
// springs are strained (coloured) as in a render, and how `bench/million.sh` renders it: 1280×720,
// 4 samples, 0.1 px particles.
struct MillionFrame {
  scenario::Scenario scene;
  render::RenderOptions options;
  render::Palette colors;
  render::Camera camera;
};
std::unique_ptr<MillionFrame> millionFrame(int threads) {
  auto m = std::make_unique<MillionFrame>(MillionFrame{
      scenario::loadScenarioFile(std::string(PARTICLES_SOURCE_DIR) + "/scenarios/cloth_million.yaml"), {}, {}, {}});
  m->scene.system.setThreads(threads);
  Stepper(m->scene.system, m->scene.simulation.integrator, m->scene.simulation.dt).advanceTo(0.01);
  m->options.width = 1280;
  m->options.height = 720;
  m->options.msaa = 4;
  m->options.particleRadius = {0.1, render::Length::Unit::pixels};
  m->colors = render::theme(m->options.themeName);
  m->camera = {m->scene.render.viewCenter, m->scene.render.viewHeight};
  return m;
}

// One frame of it into `bins`, as a render builds it: drawn, its records built and binned on the
// cloth's threads.
void buildMillionTiles(MillionFrame& m, Drawing& frame, render::TileBins& bins) {
  System& system = m.scene.system;
  system.draw(frame);
  bins.reset(m.options.width, m.options.height);
  render::buildFrameTiles(frame, m.camera, m.options, m.colors, bins, system.pool());
  bins.bin(system.pool());
}

// Building one frame of the 1000² cloth for the tile path, without GL: System::draw, the shapes'
// records (render/frame_mesh.hpp's buildFrameTiles) and their sort into tiles (TileBins::bin), on a
// pool of the argument's threads (the target: 2 threads ≥ 1.8× one).
void BM_BuildFrameMillion(benchmark::State& state) {
  const auto m = millionFrame(int(state.range(0)));
  render::TileBins bins;
  Drawing frame;  // reused, as `particles render` does
  for (auto _ : state) {
    buildMillionTiles(*m, frame, bins);
    benchmark::DoNotOptimize(bins.items().data());
  }
  state.counters["shapes"] = double(bins.shapes().size());
  state.counters["listed"] = double(bins.items().size());
}
BENCHMARK(BM_BuildFrameMillion)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

// Compositing that frame on the cpu path (render/tile_composite.hpp), its records and bins built
// once, on a pool of the argument's threads: what a frame of `bench/million.sh` or the server
// table's frames1000 row spends beyond building the frame.
void BM_CompositeMillion(benchmark::State& state) {
  const auto m = millionFrame(2);
  render::TileBins bins;
  Drawing frame;
  buildMillionTiles(*m, frame, bins);
  render::CompositedFrame image;
  image.image = render::Image(m->options.width, m->options.height);
  WorkerPool pool(int(state.range(0)));
  for (auto _ : state) {
    render::compositeTiles(bins, m->options.msaa, m->colors.background, false, image, &pool);
    benchmark::DoNotOptimize(image.image.rgba.data());
  }
  state.counters["listed"] = double(bins.items().size());
  state.counters["ns_per_listed"] = benchmark::Counter(double(state.iterations()) * double(bins.items().size()) * 1e-9,
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CompositeMillion)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(BM_Render, cloth, std::string("cloth.yaml"), 2.5)
    ->Arg(1)
    ->Arg(4)
    ->Arg(16)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Render, soft_body, std::string("soft_body.yaml"), 20.0)
    ->Arg(1)
    ->Arg(4)
    ->Arg(16)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Render, rigid_chain, std::string("rigid_chain.yaml"), 3.0)
    ->Arg(1)
    ->Arg(4)
    ->Arg(16)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The cloth demo's frame at 2.5 s, its springs by index (as `particles render` draws it), with its
// camera and the demo's look: 1280×720, 4 samples.
struct ClothDemoFrame {
  Drawing drawing;
  render::Camera camera;
  render::RenderOptions options;
};
ClothDemoFrame clothDemoFrame() {
  scenario::Scenario s = scenario::loadScenarioFile(std::string(PARTICLES_SOURCE_DIR) + "/scenarios/cloth.yaml");
  Stepper(s.system, s.simulation.integrator, s.simulation.dt).advanceTo(2.5);
  ClothDemoFrame f;
  s.system.draw(f.drawing, SpringDetail::topology);
  f.camera = {s.render.viewCenter, s.render.viewHeight};
  f.options.width = 1280;
  f.options.height = 720;
  f.options.msaa = 4;
  return f;
}

// What a frame of the cloth demo (at 2.5 s, 4 samples, 1280×720) costs by part, on the resident
// path: the whole frame (0), without its springs (1), without springs and particles (2: the guide,
// the cursor, the clear and the read-back) and an empty drawing (3: the clear and the read-back).
// The differences are the springs' and the particles' share; bench/README.md, "The resident path".
void BM_RenderDemoParts(benchmark::State& state) {
  auto [drawing, camera, options] = clothDemoFrame();
  options.raster = render::Raster::resident;
  render::Renderer renderer(options, glRequestFromEnvironment());
  const int part = int(state.range(0));
  if (part >= 1) drawing.springTopology = nullptr;
  if (part >= 2) {
    drawing.particles.clear();
    drawing.particleFixed.clear();
  }
  if (part >= 3) drawing = Drawing{};
  static const char* const kParts[] = {"whole frame", "no springs", "no springs or particles", "empty"};
  state.SetLabel(std::string(render::glBackendName(renderer.gl().backend)) + " " + kParts[part]);
  for (auto _ : state) {
    const render::Image& image = renderer.render(drawing, camera);
    benchmark::DoNotOptimize(image.rgba.data());
  }
}

BENCHMARK(BM_RenderDemoParts)->DenseRange(0, 3)->UseRealTime()->Unit(benchmark::kMillisecond);

// The cloth demo's frame (as BM_RenderDemoParts) drawn by the program's own thread, without GL
// (the cpu raster path, render/tile_composite.hpp): the shapes' records and their sort into tiles,
// then the tiles composited into the image (0), or the records and the sort alone (1).
void BM_CpuTilesDemo(benchmark::State& state) {
  const auto [drawing, camera, options] = clothDemoFrame();
  const render::Palette colors = render::theme(options.themeName);
  render::TileBins bins;
  render::CompositedFrame image;
  image.image = render::Image(options.width, options.height);
  const bool composite = state.range(0) == 0;
  state.SetLabel(composite ? "records, bins and composite" : "records and bins");
  for (auto _ : state) {
    bins.reset(options.width, options.height);
    render::buildFrameTiles(drawing, camera, options, colors, bins);
    bins.bin();
    if (composite) render::compositeTiles(bins, options.msaa, colors.background, false, image);
    benchmark::DoNotOptimize(image.image.rgba.data());
  }
  state.counters["listed"] = double(bins.items().size());
}

BENCHMARK(BM_CpuTilesDemo)->DenseRange(0, 1)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
