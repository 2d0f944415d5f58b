// Cost of one System::derivEval on the report's cloth (docs/physics.md §8), scaled up: N×N particles,
// structural springs only, stiffness 25 at the top row to 1 at the bottom, k_d 0.2, gravity and
// drag, top row on horizontal-line constraints (the rail). Spacing 0.08 m, 0.05 kg per particle and
// drag 0.05: heavier than scenarios/cloth.yaml (2 g), which changes how far the springs stretch
// but not the work per spring, the thing measured; kept so the figures in bench/README.md stay
// comparable across runs.
//
// Three variants per size, so the stages can be told apart:
//   BM_DerivEval_ClothOnRail   the whole evaluation, rail constraints solved (N rows, CG)
//   BM_DerivEval_Cloth         the same cloth without the rail: forces and stage 5 only
//   BM_SpringForce_Apply       DampedSpringForce::apply alone, the spring loop itself
// The counter `time_per_spring` is CPU time per evaluation divided by the spring count, 2·N·(N−1).
//
// The state is the cloth after 10 RK4 steps of 0.01 s from rest, so springs are stretched and
// moving (the spring loop has no state-dependent branch apart from the |l| → 0 guard, but the
// rail solve's right-hand side does depend on the state).

#include <benchmark/benchmark.h>

#include <memory>

#include "core/forces/damped_spring_force.hpp"
#include "core/forces/drag_force.hpp"
#include "core/forces/gravity_force.hpp"
#include "core/grid.hpp"
#include "core/constraints/horizontal_line_constraint.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"

namespace {

using namespace particles;

struct Cloth {
  System system;
  const DampedSpringForce* springs;
};

Cloth makeCloth(int n, bool rail) {
  SystemBuilder b;
  auto& springs = b.emplaceForce<DampedSpringForce>();
  GridSpec spec;
  spec.name = "cloth";
  spec.origin = Vec2(-1, 1);
  spec.cols = n;
  spec.rows = n;
  spec.spacing = Vec2(0.08, 0.08);
  spec.mass = 0.05;
  spec.structural = GridSpringFamily{25.0, 1.0, 0.2};
  springs.reserve(2 * size_t(n) * size_t(n - 1));
  const GridIndices g = addGrid(b, springs, spec);
  b.emplaceForce<GravityForce>(Vec2(0, -9.81));
  b.emplaceForce<DragForce>(0.05);
  if (rail) {
    for (int c = 0; c < n; ++c)
      b.addConstraint(std::make_unique<HorizontalLineConstraint>(g.at(0, c), spec.origin.y()));
  }
  Cloth cloth{b.build(), &springs};
  Solver solver(Integrator::rk4);
  for (int i = 0; i < 10; ++i) solver.doStep(cloth.system, 0.01);
  return cloth;
}

// CPU time per evaluation divided by `springs`: the counter divides the CPU seconds (Google
// Benchmark's rates use CPU time) by value × iterations. Printed as e.g. "4.2ns"; in JSON output it is in seconds.
benchmark::Counter timePerSpring(size_t springs) {
  return benchmark::Counter(double(springs),
                            benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void setCounters(benchmark::State& state, const Cloth& cloth) {
  state.counters["springs"] = double(cloth.springs->size());
  state.counters["particles"] = cloth.system.layout().numParticles;
  state.counters["time_per_spring"] = timePerSpring(cloth.springs->size());
}

void derivEval(benchmark::State& state, bool rail, int threads = 1) {
  Cloth cloth = makeCloth(int(state.range(0)), rail);
  System& sys = cloth.system;
  sys.setThreads(threads);
  state.counters["threads"] = sys.threads();
  const Eigen::VectorXd y = sys.state();
  Eigen::VectorXd dydt(y.size());
  for (auto _ : state) {
    sys.derivEval(y, sys.time(), dydt);
    benchmark::DoNotOptimize(dydt.data());
    benchmark::ClobberMemory();
  }
  setCounters(state, cloth);
  state.counters["rows"] = sys.lastConstraintSolve().rows;
}

void BM_DerivEval_ClothOnRail(benchmark::State& state) {
  derivEval(state, true);
}
void BM_DerivEval_Cloth(benchmark::State& state) {
  derivEval(state, false);
}

void BM_SpringForce_Apply(benchmark::State& state) {
  Cloth cloth = makeCloth(int(state.range(0)), false);
  const System& sys = cloth.system;
  const StateView s = sys.view();
  ForceAccumulator acc;
  acc.resize(sys.layout());
  for (auto _ : state) {
    // Not cleared between iterations: the forces pile up, which costs nothing and keeps the
    // loop the same as inside derivEval.
    cloth.springs->apply(sys.model(), s, sys.time(), acc);
    benchmark::DoNotOptimize(acc.force.data());
    benchmark::ClobberMemory();
  }
  setCounters(state, cloth);
}

// The same evaluation on T threads (System::setThreads; the second argument): wall time, since the
// work is spread over threads, and the process's CPU time beside it. The target: at 316²,
// 2 threads ≥ 1.8× one.
void BM_DerivEval_ClothThreads(benchmark::State& state) {
  derivEval(state, false, int(state.range(1)));
}

// 25: the report's cloth; 316² ≈ 10⁵ particles, 2·10⁵ springs.
BENCHMARK(BM_DerivEval_ClothOnRail)->Arg(25)->Arg(100)->Arg(316)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DerivEval_Cloth)->Arg(25)->Arg(100)->Arg(316)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SpringForce_Apply)->Arg(25)->Arg(100)->Arg(316)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DerivEval_ClothThreads)
    ->ArgsProduct({{25, 316}, {1, 2, 4, 8, 16}})
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
