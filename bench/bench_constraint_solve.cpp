// Cost of one constraint solve (docs/physics.md §2 stage 4, ConstraintSolver::solve): assemble
// J W Jᵀ λ = −J̇ q̇ − J W Q − k_s C − k_d Ċ, solve it with preconditioned CG, add Jᵀλ. Every
// scene runs with both preconditioners (argument jacobi: 0 incomplete Cholesky, 1 Jacobi); the
// automatic default picks incomplete Cholesky for chain and curtain (no loops), Jacobi for net.
//
// Scenes, all particles 0.01 kg, rods 0.02 m, gravity, at rest with every rod straight:
//   chain    one chain of R rods hanging from a fixed particle, 30° below the horizontal. J W Jᵀ
//            is tridiagonal and, for a straight chain, a 1-D Laplacian: its condition number
//            grows as R², and CG needs R − 1 iterations (measured). The hard case.
//   curtain  chains of 40 to 60 rods (cycling, the last one cut to make R) side by side, each
//            pinned at its top. Same rod count, but J W Jᵀ is block diagonal with blocks of at
//            most 60 rows: CG iterations are set by the blocks' mixed spectra, not by R. (Equal
//            blocks would let CG finish in one block's worth of iterations, which no real scene
//            offers.)
//   net      a square net of rods (closed cells, about R rods) hung by its two top corners, its
//            top edge 30° below the horizontal: loops everywhere, so the incomplete Cholesky
//            factor is not exact.
//
// Each scene is taken one RK4 step of 0.01 s from rest (integrateRk4 over System::derivEval), and
// the solve is timed at that state y₁ — the first evaluation of the second step — three ways:
//   cold       a fresh ConstraintSolver: λ starts at 0 (and its scratch is allocated on first use)
//   warm       λ from the previous evaluation, the k4 stage of step 1, as inside a running
//              System: the solver is copied before each timed solve so every solve sees that λ
//   converged  λ already solved at y₁: CG stops at once, so this is the assembly cost alone
//              (rows, triplets, the sparse product J W Jᵀ, Q̂ = Jᵀλ)
// The warm λ is obtained through public API only: a ConstraintSolver of our own is fed the same
// states and forces as the System's during its RK4 step. Only the solve call is timed (manual
// timing); copying the solver and resetting the force accumulator happen outside the clock.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <tuple>
#include <utility>

#include "core/constraints/rod_constraint.hpp"
#include "core/forces/gravity_force.hpp"
#include "core/integrators.hpp"
#include "core/integrators/rk4.hpp"
#include "core/system.hpp"

namespace {

using namespace particles;

enum class Shape { Chain, Curtain, Net };
enum class Start { Cold, Warm, Converged };

constexpr int kCurtainMinRods = 40, kCurtainMaxRods = 60;
constexpr double kRodLength = 0.02;  // m
constexpr double kMass = 0.01;       // kg per particle
constexpr double kDt = 0.01;         // s, the cloth demo's step (scenarios/cloth.yaml)

// One chain of `rods` rods from a new fixed particle at `top`, straight, at `angle` (rad).
void addChain(SystemBuilder& b, const Vec2& top, double angle, int rods) {
  ParticleSpec p;
  p.mass = kMass;
  p.pos = top;
  p.fixed = true;
  int previous = b.addParticle(p);
  p.fixed = false;
  const Vec2 step = kRodLength * Vec2(std::cos(angle), std::sin(angle));
  for (int i = 1; i <= rods; ++i) {
    p.pos = top + i * step;
    const int next = b.addParticle(p);
    b.addConstraint(std::make_unique<RodConstraint>(previous, next, kRodLength));
    previous = next;
  }
}

// A square net of rods (horizontal and vertical, closed cells) with its top row fixed, rotated 30°
// from hanging straight so it swings: about `rods` rods, n × n particles with 2n(n − 1) ≈ rods.
void addNet(SystemBuilder& b, int rods) {
  const int n = int(std::ceil(0.5 + std::sqrt(0.25 + 0.5 * rods)));
  const Vec2 right = kRodLength * Vec2(std::cos(-std::numbers::pi / 6), std::sin(-std::numbers::pi / 6));
  const Vec2 down(right.y(), -right.x());
  ParticleSpec p;
  p.mass = kMass;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      p.pos = double(c) * right + double(r) * down;
      p.fixed = r == 0 && (c == 0 || c == n - 1);  // hung by its two top corners
      b.addParticle(p);
    }
  }
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      if (c + 1 < n) b.addConstraint(std::make_unique<RodConstraint>(r * n + c, r * n + c + 1, kRodLength));
      if (r + 1 < n) b.addConstraint(std::make_unique<RodConstraint>(r * n + c, (r + 1) * n + c, kRodLength));
    }
  }
}

System makeScene(Shape shape, int rods, const ConstraintSolverOptions& options) {
  SystemBuilder b;
  b.setConstraintSolverOptions(options);
  if (shape == Shape::Chain) {
    addChain(b, Vec2(0, 0), -std::numbers::pi / 6, rods);
  } else if (shape == Shape::Net) {
    addNet(b, rods);
  } else {
    for (int k = 0, placed = 0; placed < rods; ++k) {
      const int length = std::min(kCurtainMinRods + k % (kCurtainMaxRods - kCurtainMinRods + 1), rods - placed);
      addChain(b, Vec2(0.05 * k, 0), -std::numbers::pi / 6, length);
      placed += length;
    }
  }
  b.emplaceForce<GravityForce>(Vec2(0, -9.81));
  return b.build();
}

// Stages 1–2 of derivEval: the forces the constraint solve sees (no colliders in these scenes).
void accumulateForces(const System& sys, const StateView& s, double t, ForceAccumulator& acc) {
  acc.clear();
  for (const auto& force : sys.forces()) force->apply(sys.model(), s, t, acc);
}

struct Scene {
  System system;               // at y₁, after one RK4 step
  ConstraintSolver warm;       // λ from the last evaluation of that step
  ConstraintSolver converged;  // λ solved at y₁
  ForceAccumulator forces;     // stages 1–2 at y₁
};

std::unique_ptr<Scene> prepareScene(Shape shape, int rods, const ConstraintSolverOptions& options) {
  auto scene = std::make_unique<Scene>(
      Scene{makeScene(shape, rods, options), ConstraintSolver(options), ConstraintSolver(options), {}});
  System& sys = scene->system;
  ForceAccumulator acc;
  acc.resize(sys.layout());
  const DerivFn f = [&](const Eigen::VectorXd& y, double t, Eigen::VectorXd& dydt) {
    sys.derivEval(y, t, dydt);
    const StateView s(sys.layout(), y);
    accumulateForces(sys, s, t, acc);
    scene->warm.solve(sys.model(), s, sys.constraints(), acc);
  };
  IntegratorScratch scratch;
  integrateRk4(f, sys.state(), sys.time(), kDt, scratch);
  sys.setTime(sys.time() + kDt);

  scene->forces.resize(sys.layout());
  accumulateForces(sys, sys.view(), sys.time(), scene->forces);
  scene->converged = scene->warm;
  acc = scene->forces;
  scene->converged.solve(sys.model(), sys.view(), sys.constraints(), acc);
  return scene;
}

// Preparing the 10⁴-rod chain costs eight slow solves; every run of a benchmark (repetitions,
// the iteration-count probe) reuses it.
const Scene& scene(Shape shape, int rods, Preconditioner preconditioner) {
  static std::map<std::tuple<Shape, int, Preconditioner>, std::unique_ptr<Scene>> cache;
  auto& entry = cache[{shape, rods, preconditioner}];
  ConstraintSolverOptions options;
  options.preconditioner = preconditioner;
  if (!entry) entry = prepareScene(shape, rods, options);
  return *entry;
}

void BM_ConstraintSolve(benchmark::State& state, Shape shape, Start start) {
  ConstraintSolverOptions options;
  options.preconditioner = state.range(1) == 0 ? Preconditioner::incompleteCholesky : Preconditioner::jacobi;
  const Scene& sc = scene(shape, int(state.range(0)), options.preconditioner);
  const System& sys = sc.system;
  const StateView s = sys.view();
  ConstraintSolveStats stats;
  for (auto _ : state) {
    ConstraintSolver solver(options);
    if (start == Start::Warm) solver = sc.warm;
    if (start == Start::Converged) solver = sc.converged;
    ForceAccumulator acc = sc.forces;
    const auto begin = std::chrono::steady_clock::now();
    stats = solver.solve(sys.model(), s, sys.constraints(), acc);
    const auto end = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(acc.force.data());
    state.SetIterationTime(std::chrono::duration<double>(end - begin).count());
  }
  state.counters["rows"] = stats.rows;
  state.counters["cg_iterations"] = stats.iterations;
  state.counters["rel_residual"] = stats.relativeResidual;
}

// Arguments: rods, preconditioner (0 incomplete Cholesky, the default; 1 Jacobi).
void solveArgs(benchmark::internal::Benchmark* b) {
  b->ArgNames({"rods", "jacobi"});
  for (int rods : {1000, 10000}) {
    for (int jacobi : {0, 1}) b->Args({rods, jacobi});
  }
  b->UseManualTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK_CAPTURE(BM_ConstraintSolve, chain_cold, Shape::Chain, Start::Cold)->Apply(solveArgs);
BENCHMARK_CAPTURE(BM_ConstraintSolve, chain_warm, Shape::Chain, Start::Warm)->Apply(solveArgs);
BENCHMARK_CAPTURE(BM_ConstraintSolve, chain_converged, Shape::Chain, Start::Converged)->Apply(solveArgs);
BENCHMARK_CAPTURE(BM_ConstraintSolve, curtain_cold, Shape::Curtain, Start::Cold)->Apply(solveArgs);
BENCHMARK_CAPTURE(BM_ConstraintSolve, curtain_warm, Shape::Curtain, Start::Warm)->Apply(solveArgs);
BENCHMARK_CAPTURE(BM_ConstraintSolve, curtain_converged, Shape::Curtain, Start::Converged)->Apply(solveArgs);
BENCHMARK_CAPTURE(BM_ConstraintSolve, net_cold, Shape::Net, Start::Cold)->Apply(solveArgs);
BENCHMARK_CAPTURE(BM_ConstraintSolve, net_warm, Shape::Net, Start::Warm)->Apply(solveArgs);
BENCHMARK_CAPTURE(BM_ConstraintSolve, net_converged, Shape::Net, Start::Converged)->Apply(solveArgs);

}  // namespace
