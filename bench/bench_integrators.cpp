// Cost of one Solver::doStep per integrator, and per simulated second at the step each can use:
//   - the demo cloth (scenarios/cloth.yaml: 25 × 25, structural springs 25 → 1 N/m, 2 g particles,
//     rail, mouse) at 25² and at 316² (99,856 particles, 199,080 springs over the same 1.92 m
//     square, as in bench_render.cpp's large cloth), each integrator at the largest step without
//     shaking that `particles stability` found on that cloth, backward Euler at one step per
//     60 fps frame;
//   - the stiff cloth (scenarios/cloth_stiff.yaml: the same springs × 100) at 25², the explicit
//     integrators at their limits there, backward Euler at one step per frame.
// A run that blows up is reported as an error, not timed.
//
// The scene is advanced to t = 1 s first (RK4 at 0.01 s; backward Euler at 1/60 s for the stiff
// cloth), and one step of the integrator under test is taken, all outside the clock (the first
// step builds backward Euler's matrix pattern and Verlet's first evaluation); each iteration is then one step from
// where the last one ended, so the benchmark walks through the scene's motion, for kRewindSteps steps, then goes back
// to the state after that first step (outside the clock) and walks again: a study's step limit holds over the span it
// studied (1.5 s for the 316² cloth), and symplectic Euler at its 316² limit blows up 100 steps (0.67 s) after t = 1 s.
// Counters:
//   sim_s_cost      CPU seconds per simulated second: time per step / dt
//   per_particle    CPU time per step divided by the particle count
//   cg_iterations   the implicit integrators' PCG iterations per step (mean; 0 on a step the direct
//                   solve answered from fresh factors)
//   factorizations  the direct solve's numeric factorisations per step (mean)
// BM_SceneRun: a whole scene at dt per iteration (see there); BM_ImplicitCrossover: auto's rule;
// BM_CgPreconditioner: Jacobi against incomplete Cholesky on one step's A.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <string>
#include <vector>

#include "core/integrators/backward_euler.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"
#include "scenario/scenario.hpp"

namespace {

using namespace particles;

scenario::Scenario loadCloth(const std::string& file, int n) {
  std::vector<scenario::Override> overrides;
  if (n != 25) {
    overrides = {scenario::parseOverride(fmt::format("grids.0.size=[{0}, {0}]", n)),
                 scenario::parseOverride(fmt::format("grids.0.spacing=[{0}, {0}]", 1.92 / double(n - 1))),
                 scenario::parseOverride(fmt::format("mouse.0.grab=cloth[{}][{}]", n - 1, n / 2))};
  }
  return scenario::loadScenarioFile(std::string(PARTICLES_SOURCE_DIR) + "/scenarios/" + file, overrides);
}

constexpr long kRewindSteps = 50;

void BM_IntegratorStep(benchmark::State& state, const std::string& file, int n, Integrator integrator, double dt,
                       int threads = 1, ImplicitSolver solve = ImplicitSolver::automatic) {
  scenario::Scenario s = loadCloth(file, n);
  s.system.setThreads(threads);
  const bool stiff = file != "cloth.yaml";
  Stepper(s.system, stiff ? Integrator::backwardEuler : Integrator::rk4, stiff ? 1.0 / 60.0 : 0.01).advanceTo(1.0);
  s.system.setImplicitSolver(solve);
  Solver solver(integrator);
  // One step outside the clock: Verlet's first evaluation, backward Euler's matrix pattern.
  try {
    solver.doStep(s.system, dt);
  } catch (const SimulationError& e) {
    state.SkipWithError(e.what());
    return;
  }
  state.SetLabel(fmt::format("{} dt={:.2g}", integratorName(integrator), dt));
  const Eigen::VectorXd start = s.system.state();
  const double startTime = s.system.time();
  long cgIterations = 0, sinceStart = 0;
  const long factorizationsBefore = solver.factorizations();
  for (auto _ : state) {
    if (sinceStart == kRewindSteps) {
      state.PauseTiming();
      s.system.state() = start;
      s.system.setTime(startTime);
      sinceStart = 0;
      state.ResumeTiming();
    }
    ++sinceStart;
    try {
      solver.doStep(s.system, dt);
    } catch (const SimulationError& e) {
      state.SkipWithError(e.what());
      break;
    }
    cgIterations += solver.lastImplicitStep().iterations;
  }
  const double particles = double(s.system.layout().numPoints());
  state.counters["sim_s_cost"] = benchmark::Counter(dt, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["per_particle"] =
      benchmark::Counter(particles, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  if (isImplicit(integrator) && state.iterations() > 0) {
    state.counters["cg_iterations"] = double(cgIterations) / double(state.iterations());
    state.counters["factorizations"] =
        double(solver.factorizations() - factorizationsBefore) / double(state.iterations());
  }
}

// The largest steps without shaking (docs/stability.md for the 25² cloths; the 316² cloth's from
// its own study over 1.5 s, bench/README.md); backward Euler: one 60 fps frame.
constexpr double kFrame = 1.0 / 60.0;

struct Case {
  const char* scene;
  int n;
  Integrator integrator;
  double dt;
  ImplicitSolver solve = ImplicitSolver::automatic;  // named in the benchmark when not auto
};

const Case kCases[] = {
    {"cloth.yaml", 25, Integrator::euler, 0.00054},       {"cloth.yaml", 25, Integrator::midpoint, 0.0034},
    {"cloth.yaml", 25, Integrator::rk4, 0.012},           {"cloth.yaml", 25, Integrator::symplecticEuler, 0.0081},
    {"cloth.yaml", 25, Integrator::verlet, 0.0077},       {"cloth.yaml", 25, Integrator::backwardEuler, kFrame},
    {"cloth.yaml", 316, Integrator::euler, 0.00069},      {"cloth.yaml", 316, Integrator::midpoint, 0.0034},
    {"cloth.yaml", 316, Integrator::rk4, 0.01},           {"cloth.yaml", 316, Integrator::symplecticEuler, 0.0067},
    {"cloth.yaml", 316, Integrator::verlet, 0.0064},      {"cloth.yaml", 316, Integrator::backwardEuler, kFrame},
    {"cloth_stiff.yaml", 25, Integrator::midpoint, 0.00016}, {"cloth_stiff.yaml", 25, Integrator::rk4, 0.0012},
    {"cloth_stiff.yaml", 25, Integrator::symplecticEuler, 0.00089},
    {"cloth_stiff.yaml", 25, Integrator::verlet, 0.00088}, {"cloth_stiff.yaml", 25, Integrator::backwardEuler, kFrame},
    // BDF2, the direct solve beside CG, and the 10⁴× stiff cloth (its limits from
    // `particles stability scenarios/cloth_very_stiff.yaml`, docs/stability.md).
    {"cloth.yaml", 25, Integrator::bdf2, kFrame},
    {"cloth.yaml", 25, Integrator::backwardEuler, kFrame, ImplicitSolver::cg},
    {"cloth.yaml", 316, Integrator::backwardEuler, kFrame, ImplicitSolver::direct},
    {"cloth.yaml", 316, Integrator::bdf2, kFrame},
    {"cloth_stiff.yaml", 25, Integrator::bdf2, kFrame},
    {"cloth_stiff.yaml", 25, Integrator::backwardEuler, kFrame, ImplicitSolver::cg},
    {"cloth_very_stiff.yaml", 25, Integrator::rk4, 0.00012},
    {"cloth_very_stiff.yaml", 25, Integrator::symplecticEuler, 0.000089},
    {"cloth_very_stiff.yaml", 25, Integrator::verlet, 0.000089},
    {"cloth_very_stiff.yaml", 25, Integrator::backwardEuler, kFrame},
    {"cloth_very_stiff.yaml", 25, Integrator::bdf2, kFrame},
    {"cloth_very_stiff.yaml", 25, Integrator::backwardEuler, kFrame, ImplicitSolver::cg},
};

// A scenario file's name without its extension: cloth_stiff for cloth_stiff.yaml.
std::string sceneStem(const std::string& file) {
  return file.substr(0, file.find('.'));
}

std::string caseName(const char* prefix, const Case& c) {
  const std::string scene = sceneStem(c.scene);
  std::string name = fmt::format("{}/{}/{}/{}", prefix, scene, c.n, integratorName(c.integrator));
  if (c.solve != ImplicitSolver::automatic) name += fmt::format("/{}", implicitSolverName(c.solve));
  return name;
}

// A whole scene, 0 to its duration (10 s) at dt, per iteration (loading outside the clock): the
// cost per simulated second over everything the scene does (the 50-step walks of
// BM_IntegratorStep see 0.8 s of it; the direct solve's factors last longer while the cloth hangs
// still than while the mouse drags it).
void BM_SceneRun(benchmark::State& state, const Case& c) {
  long steps = 0;
  double duration = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    scenario::Scenario s = loadCloth(c.scene, c.n);
    s.system.setImplicitSolver(c.solve);
    duration = s.simulation.duration;
    Stepper stepper(s.system, c.integrator, c.dt);
    state.ResumeTiming();
    try {
      stepper.advanceTo(duration);
    } catch (const SimulationError& e) {
      state.SkipWithError(e.what());
      break;
    }
    steps += stepper.steps();
  }
  state.counters["sim_s_cost"] =
      benchmark::Counter(duration, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  if (state.iterations() > 0) state.counters["steps"] = double(steps) / double(state.iterations());
}

// auto's crossover (core/implicit_step.hpp, autoDirectIterations): backward Euler over the first 3 s
// at one step per frame, CG against direct, on the demo cloth scaled to n² particles over the same
// square. Counters: per_step (CPU time a step), cg_iterations (PCG iterations a step, mean) and
// factorizations (in the 180 steps); the break-even CG iterations at a size are direct's time a
// step over CG's time per iteration.
void BM_ImplicitCrossover(benchmark::State& state, const char* scene, int n, ImplicitSolver solve) {
  long steps = 0, iterations = 0, factorizations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    scenario::Scenario s = loadCloth(scene, n);
    s.system.setImplicitSolver(solve);
    Solver solver(Integrator::backwardEuler);
    state.ResumeTiming();
    for (int step = 0; step < 180; ++step) {
      solver.doStep(s.system, kFrame);
      iterations += solver.lastImplicitStep().iterations;
    }
    steps += 180;
    factorizations += solver.factorizations();
  }
  state.counters["per_step"] =
      benchmark::Counter(double(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["cg_iterations"] = double(iterations) / double(std::max(steps, 1L));
  state.counters["factorizations"] =
      double(factorizations) / double(std::max(state.iterations(), benchmark::IterationCount(1)));
}

// The CG path's preconditioner: is block-Jacobi or incomplete Cholesky worth it in the large case?
// A and b of one backward Euler step of the n² demo cloth at t = 1 s (its rail's and fixed points'
// rows the identity, no constraint rows: the preconditioners alone), solved to 1e-6 by Eigen's CG
// with Jacobi or with Eigen's IncompleteCholesky (AMD ordering; its factorisation inside the
// clock, as each step's new A would need). Counters: iterations.
enum class CgPreconditioner { jacobi, incompleteCholesky };
void BM_CgPreconditioner(benchmark::State& state, const char* scene, int n, CgPreconditioner which) {
  scenario::Scenario s = loadCloth(scene, n);
  const bool stiff = std::string(scene) != "cloth.yaml";
  Stepper(s.system, stiff ? Integrator::backwardEuler : Integrator::rk4, stiff ? kFrame : 0.01).advanceTo(1.0);
  s.system.setImplicitSolver(ImplicitSolver::cg);
  BackwardEulerState w;
  Eigen::VectorXd y = s.system.state();
  w.step(s.system, y, s.system.time(), kFrame);
  const ImplicitStep::LinearSystem step = w.implicitStep()->lastSystem();
  const Eigen::SparseMatrix<double>& a = step.matrix;
  const Eigen::VectorXd& b = step.rhs;
  long iterations = 0;
  for (auto _ : state) {
    if (which == CgPreconditioner::jacobi) {
      Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
      cg.setTolerance(1e-6);
      cg.compute(a);
      Eigen::VectorXd x = cg.solve(b);  // a variable: DoNotOptimize takes no const temporary since 1.9
      benchmark::DoNotOptimize(x);
      iterations += cg.iterations();
    } else {
      Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                               Eigen::IncompleteCholesky<double>>
          cg;
      cg.setTolerance(1e-6);
      cg.compute(a);
      Eigen::VectorXd x = cg.solve(b);  // a variable: DoNotOptimize takes no const temporary since 1.9
      benchmark::DoNotOptimize(x);
      iterations += cg.iterations();
    }
  }
  state.counters["iterations"] =
      double(iterations) / double(std::max(state.iterations(), benchmark::IterationCount(1)));
}

// Side by side per cloth: symplectic Euler at its limit (the cheapest explicit integrator per
// simulated second on all three), RK4 at its limit, and the implicit ones at one step per frame.
const Case kRuns[] = {
    {"cloth.yaml", 25, Integrator::symplecticEuler, 0.0081},
    {"cloth.yaml", 25, Integrator::backwardEuler, kFrame},
    {"cloth.yaml", 25, Integrator::backwardEuler, kFrame, ImplicitSolver::cg},
    {"cloth.yaml", 25, Integrator::backwardEuler, kFrame, ImplicitSolver::direct},
    {"cloth.yaml", 25, Integrator::bdf2, kFrame},
    {"cloth_stiff.yaml", 25, Integrator::symplecticEuler, 0.00089},
    {"cloth_stiff.yaml", 25, Integrator::rk4, 0.0012},
    {"cloth_stiff.yaml", 25, Integrator::backwardEuler, kFrame},
    {"cloth_stiff.yaml", 25, Integrator::backwardEuler, kFrame, ImplicitSolver::cg},
    {"cloth_stiff.yaml", 25, Integrator::bdf2, kFrame},
    {"cloth_very_stiff.yaml", 25, Integrator::symplecticEuler, 0.000089},
    {"cloth_very_stiff.yaml", 25, Integrator::rk4, 0.00012},
    {"cloth_very_stiff.yaml", 25, Integrator::backwardEuler, kFrame},
    {"cloth_very_stiff.yaml", 25, Integrator::backwardEuler, kFrame, ImplicitSolver::cg},
    {"cloth_very_stiff.yaml", 25, Integrator::bdf2, kFrame},
};

// Names read BM_IntegratorStep/cloth_stiff/25/rk4, BM_IntegratorStep/cloth/25/backward_euler/cg.
const bool kRegistered = [] {
  for (const Case& c : kCases) {
    benchmark::RegisterBenchmark(caseName("BM_IntegratorStep", c).c_str(), [c](benchmark::State& state) {
      BM_IntegratorStep(state, c.scene, c.n, c.integrator, c.dt, 1, c.solve);
    })->Unit(c.n > 100 ? benchmark::kMillisecond : benchmark::kMicrosecond);
  }
  for (const Case& c : kRuns) {
    benchmark::RegisterBenchmark(caseName("BM_SceneRun", c).c_str(), [c](benchmark::State& state) {
      BM_SceneRun(state, c);
    })->Unit(benchmark::kMillisecond);
  }
  for (const char* scene : {"cloth.yaml", "cloth_stiff.yaml"}) {
    for (int n : {25, 50, 100, 141}) {
      if (std::string(scene) != "cloth.yaml" && n > 50) continue;
      for (ImplicitSolver solve : {ImplicitSolver::cg, ImplicitSolver::direct}) {
        const std::string name =
            fmt::format("BM_ImplicitCrossover/{}/{}/{}", sceneStem(scene), n, implicitSolverName(solve));
        benchmark::RegisterBenchmark(name.c_str(), [scene, n, solve](benchmark::State& state) {
          BM_ImplicitCrossover(state, scene, n, solve);
        })->Unit(benchmark::kMillisecond);
      }
    }
  }
  for (const char* scene : {"cloth.yaml", "cloth_stiff.yaml"}) {
    for (int n : {100, 316}) {
      if (std::string(scene) != "cloth.yaml" && n > 100) continue;
      for (CgPreconditioner which : {CgPreconditioner::jacobi, CgPreconditioner::incompleteCholesky}) {
        const std::string name = fmt::format("BM_CgPreconditioner/{}/{}/{}", sceneStem(scene), n,
                                             which == CgPreconditioner::jacobi ? "jacobi" : "incomplete_cholesky");
        benchmark::RegisterBenchmark(name.c_str(), [scene, n, which](benchmark::State& state) {
          BM_CgPreconditioner(state, scene, n, which);
        })->Unit(benchmark::kMillisecond);
      }
    }
  }
  // The step targets: the 316² cloth on 1 and 2 threads (System::setThreads), wall time.
  for (Integrator integrator : {Integrator::rk4, Integrator::symplecticEuler, Integrator::backwardEuler}) {
    for (const Case& c : kCases) {
      if (c.n != 316 || c.integrator != integrator || c.solve != ImplicitSolver::automatic) continue;
      for (int threads : {1, 2, 4, 8, 16}) {
        const std::string name =
            fmt::format("BM_IntegratorStepThreads/cloth/316/{}/threads:{}", integratorName(integrator), threads);
        benchmark::RegisterBenchmark(name.c_str(),
                                     [c, threads](benchmark::State& state) {
                                       BM_IntegratorStep(state, c.scene, c.n, c.integrator, c.dt, threads);
                                     })
            ->UseRealTime()
            ->MeasureProcessCPUTime()
            ->Unit(benchmark::kMillisecond);
      }
    }
  }
  return true;
}();

}  // namespace
