// Render-only throughput (no encoding): frames per second drawing the three demos at 1280×720
// through the renderer's default GL backend (PARTICLES_GL=egl or osmesa picks one, as for
// `particles render`; the label names it), with 1 (off), 4 (the default) and 16 anti-aliasing
// samples per pixel. Each iteration draws one frame of a state prepared beforehand (the scenario
// advanced to a representative time), so simulation is outside the clock; System::draw() is called
// inside it, as `particles render` does per frame.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>

#include "render/renderer.hpp"
#include "core/drawing.hpp"
#include "core/system.hpp"
#include "scenario/scenario.hpp"
#include "core/solver.hpp"

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

}  // namespace
