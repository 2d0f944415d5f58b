#pragma once
// The implicit integrators' common step (backward Euler, BDF2; docs/physics.md §3): one Newton
// step of a linearly implicit formula
//   v₁ = v̄ + η M⁻¹ f(x₁, v₁),   x₁ = x̄ + η v₁
// linearised at a state (x_b, v_b) with the force Jacobians K = ∂f/∂x, D = ∂f/∂v there
// (core/force_jacobians.hpp), for Δv = v₁ − v_b:
//   (M − η D − η² K) Δv = M (v̄ − v_b) + η (f_b + K (x̄ − x_b + η v_b))
// Backward Euler is x̄ = x_b = x₀, v̄ = v_b = v₀, η = h (Baraff & Witkin 1998, eq. 16–18); BDF2
// is x̄ = (4 x₀ − x₋₁)/3, v̄ = (4 v₀ − v₋₁)/3, η = 2h/3 (Choi & Ko 2002), linearised at the
// extrapolated end (x_b, v_b) = 2 (x₀, v₀) − (x₋₁, v₋₁) (integrators/bdf2.hpp says why).
//
// The matrix A = M − η D − η² K is sparse, symmetric and positive definite. Constraints are part
// of the solve: Δv keeps J Δv = −J v₀ (J at x₀), so v₁ has Ċ = 0 and stiff springs feel the rail
// that holds the cloth within the same step. Two ways to solve (core/implicit_solver.hpp):
//   - CG: projected conjugate gradients (core/projected_pcg.hpp) with a Jacobi preconditioner;
//     fixed particles' coordinates pinned at Δv = 0, every constraint row by projection.
//   - direct: reduced coordinates, then a sparse LDLᵀ of A (core/preconditioners/ldlt_
//     preconditioner.hpp). A fixed particle's coordinates, and a coordinate that an axis-aligned
//     rail fixes (a constraint row on one particle whose J has one non-zero component: Δv_i =
//     c / J_i), leave the unknowns: their rows and columns of A become the identity and their
//     known Δv moves to the right-hand side. The other rows go through the Schur complement. The
//     factors are reused across steps as the preconditioner of the same projected PCG, which
//     refines the answer to kDirectTolerance (A's own factors answer at once), and are refactored
//     when what reuse has cost since the last factorisation (the extra solves and products, in
//     counted multiply-adds, so that the choice does not depend on timing or thread count) adds
//     up to one factorisation.
// Rigid bodies: their centres' translation is in the solve; their rotation is explicit, symplectic
// Euler with the torque at the step's start: ω₁ = ω₀ + h τ₀/I, θ₁ = θ₀ + h ω₁.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "core/constraint.hpp"
#include "core/implicit_solver.hpp"
#include "core/preconditioners/ldlt_preconditioner.hpp"

namespace particles {

class System;

// auto's rule. CG's cost grows with the stiffness (its iterations, like h √(k/m)), the direct
// solve's with the size (its factor's fill), so auto starts with CG and moves to the direct solve,
// for the rest of the run, once CG's last kAutoWindow steps needed more iterations on average than
// the direct solve costs in CG iterations at that size: 14 · (free coordinates / 1250)^0.3.
// The rule fits the break-even counts measured on the demo cloth scaled to n², where the stiff
// cloths' counts fall on the direct side (bench/README.md, "The crossover"; BM_ImplicitCrossover).
// Only when the other constraint rows are few enough for the Schur complement (kMaxSchurRows).
double autoDirectIterations(long freeCoordinates);
constexpr int kAutoWindow = 10;
// The direct path's iterations on an earlier step's factors stop at this relative error in the
// energy norm (core/projected_pcg.hpp), two digits below CG's; A's own factors answer exactly, in
// one solve. A tighter one costs more iterations on stale factors and more refactorisations: the
// 10⁴× stiff cloth's step at 1e-6, 1e-8 and 1e-10 is timed in bench/README.md, "Implicit
// integration".
constexpr double kDirectTolerance = 1e-8;
// CG's relative residual (each step starts from the last one's Δv).
constexpr double kCgTolerance = 1e-6;
// Iterations the direct path gives stale factors before it refactors within the step.
constexpr int kMaxReuseIterations = 20;

// What the last implicit step did, for benchmarks and tests.
struct ImplicitStepStats {
  ImplicitSolver solver = ImplicitSolver::cg;  // the one used (never automatic)
  int iterations = 0;                          // PCG iterations
  bool factorized = false;                     // the direct path refactored this step
  int eliminated = 0;                          // coordinates eliminated by rails
  int schurRows = 0;                           // constraint rows through the Schur complement
};

// The step's target: η and, for BDF2, x̄ − x_b and v̄ − v_b, where (x_b, v_b) is the state y the
// step is linearised at (null: zero, backward Euler, linearised at the step's start). BDF2
// linearises at a predicted end (see integrators/bdf2.hpp) and gives the state its rigid bodies'
// rotation starts from (rotationStart; null: y's own).
struct ImplicitTarget {
  double eta = 0.0;
  const Eigen::VectorXd* xShift = nullptr;
  const Eigen::VectorXd* vShift = nullptr;
  const Eigen::VectorXd* rotationStart = nullptr;
};

// The common step with what it keeps between steps: A's pattern, the last Δv (CG's first guess),
// the direct path's factors and its reuse account, and auto's choice. Each implicit integrator
// owns one (integrators/backward_euler.hpp, integrators/bdf2.hpp); the scratch the stages fill is
// core/implicit_assembly.hpp's, internal to the core.
class ImplicitStep {
 public:
  ImplicitStep();
  ~ImplicitStep();
  ImplicitStep(ImplicitStep&&) noexcept;
  ImplicitStep& operator=(ImplicitStep&&) noexcept;

  // One step by h: y holds the state the step is linearised at, taken at time t, and receives the
  // step's end. Throws ImplicitSolverError when the scene's implicit solver is `direct` and more
  // constraint rows than kMaxSchurRows are neither fixed points nor rails.
  void step(System& system, Eigen::VectorXd& y, double t, double h, const ImplicitTarget& target,
            double cgTolerance = kCgTolerance);

  const ImplicitStepStats& stats() const;  // the last step's
  long factorizations() const;             // the direct path's, so far

  // The last step's linear system, A Δv = b with J Δv = c: for tests that check the solves
  // against a dense one. matrix is A over every coordinate (an eliminated or fixed one's row and
  // column the identity), rhs is b, dv the answer, constraintRows J's rows at the step's start.
  struct LinearSystem {
    const Eigen::SparseMatrix<double>& matrix;
    const Eigen::VectorXd& rhs;
    const Eigen::VectorXd& dv;
    const std::vector<ConstraintRow>& constraintRows;
  };
  LinearSystem lastSystem() const;

  // What the step's stages fill and keep: defined in core/implicit_assembly.hpp, for them alone.
  struct Scratch;

 private:
  std::unique_ptr<Scratch> w_;
};

}  // namespace particles
