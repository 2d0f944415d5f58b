// The public C++ API (include/particles/), the baseline of the Python module's targets
// (bench/python_api.py runs these and the same calls from Python and prints the ratios):
//   - one step of the 25² cloth demo (RK4, dt 0.01) through Simulation::step(), one thread;
//   - one frame of the cloth at 320×240 through Renderer::render() (msaa 4, the dark theme), the
//     state left as it is (the clock counts drawing and the copy into the Image, not stepping);
//   - one step of a 316² cloth (99,856 particles) on one thread: the work each of two Python
//     threads does in the GIL target; and two such simulations on two threads, the C++ ceiling.
#include <benchmark/benchmark.h>

#include <string>

#include <particles/particles.hpp>

namespace {

std::string clothPath() { return std::string(PARTICLES_SOURCE_DIR) + "/scenarios/cloth.yaml"; }

void BM_ApiStepCloth25(benchmark::State& state) {
  particles::Simulation sim(particles::Scenario::load(clothPath()), 1);
  for (auto _ : state) sim.step();
  state.counters["us_per_step"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate |
                                                                                     benchmark::Counter::kInvert);
}
BENCHMARK(BM_ApiStepCloth25)->Unit(benchmark::kMicrosecond)->UseRealTime();

void BM_ApiRenderCloth320x240(benchmark::State& state) {
  particles::Simulation sim(particles::Scenario::load(clothPath()), 1);
  sim.advance(2.5);
  particles::Renderer renderer({.width = 320, .height = 240});
  for (auto _ : state) {
    const particles::Image frame = renderer.render(sim);
    benchmark::DoNotOptimize(frame.rgba.data());
  }
  state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ApiRenderCloth320x240)->Unit(benchmark::kMillisecond)->UseRealTime();  // llvmpipe draws on threads of its own

void BM_ApiStepCloth316(benchmark::State& state) {
  particles::Scenario cloth = particles::Scenario::load(clothPath());
  cloth.set("grids[0].size", "[316, 316]");
  particles::Simulation sim(cloth, 1);
  for (auto _ : state) sim.step();
  state.counters["steps_per_s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
// On 1 and 2 threads, each with a simulation of its own: steps_per_s is their sum, the ceiling of
// what two Python threads can reach on this machine.
BENCHMARK(BM_ApiStepCloth316)->Unit(benchmark::kMillisecond)->UseRealTime()->Threads(1)->Threads(2);

}  // namespace
