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
#include <array>
#include <vector>

#include "core/constraint.hpp"
#include "core/force_jacobians.hpp"
#include "core/implicit_solver.hpp"
#include "core/preconditioners/jacobi_preconditioner.hpp"
#include "core/preconditioners/ldlt_preconditioner.hpp"
#include "core/projected_pcg.hpp"

namespace particles {

class System;

// auto's rule. CG's cost grows with the stiffness (its iterations, like h √(k/m)), the direct
// solve's with the size (its factor's fill), so auto starts with CG and moves to the direct solve,
// for the rest of the run, once CG's last kAutoWindow steps needed more iterations on average than
// the direct solve costs in CG iterations at that size: 14 · (free coordinates / 1250)^0.3.
// Measured over the first 3 s of backward Euler at 1/60 s on the demo cloth scaled to n²
// (bench/README.md, "Implicit integration"; BM_ImplicitCrossover): CG and direct break even at 14
// iterations on the 25² cloth (1,250 coordinates), 20 on the 50², 30 on the 100², 39 on the 141²;
// the demo cloth needs 18–20 at every size (direct wins at 25², they tie at 50², CG wins above),
// the 100× stiff one 107–165 and the 10⁴× stiff one about 400 (direct wins). Only when the other
// constraint rows are few enough for the Schur complement (kMaxSchurRows).
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

// The implicit step's matrix pattern: the Jacobians' (row, column) keys and the pinned
// coordinates it was built from, and which triplets' values go where in the compressed matrix,
// read so that threads fill whole values and rows, each summing in the triplets' order (the order
// a serial scatter adds in).
struct AssemblyPattern {
  bool valid = false;
  std::vector<int> dfdvKeys, dfdxKeys, pairKeys;
  std::vector<char> pinned;
  // Per value slot, the entries that land there (k < |D|: D's k-th, else K's (k − |D|)-th) from
  // slotStart[slot], and the coordinate whose diagonal it is (−1: none); per row of K, its
  // entries' indices from kRowStart[row]. pinnedColumnEntries: the entries (same numbering) in a
  // free row and an eliminated column, whose A value times the known Δv leaves the right-hand side.
  std::vector<int> slotStart, slotEntries, slotDiagonal, kRowStart, kRowEntries, pinnedColumnEntries;
  // The Jacobian pairs (ForceJacobians::pairs) by 2 × 2 blocks of A: pair q's block `role` (0: (a, a),
  // 1: (b, b), 2: (a, b), 3: (b, a); the last two subtract) is reference 4q + role. Each block of
  // A they reach has its four slots (xx, yx, xy, yy; −1: a pinned coordinate's) and its references
  // pairBlockRefs[begin … end), in the pairs' order. Per point, its pairs' references 2q (as a) or
  // 2q + 1 (as b) from pairPointStart[point], for K's products in b; pinnedPairEntries: (reference
  // 4q + role, r, c) whose entry (r, c) of that block is in a free row and an eliminated column.
  struct PairBlock {
    int slot[4];
    int begin, end;
  };
  std::vector<PairBlock> pairBlocks;
  std::vector<int> pairBlockRefs, pairPointStart, pairPointRefs;
  std::vector<std::array<int, 3>> pinnedPairEntries;
};

// What the last implicit step did, for benchmarks and tests.
struct ImplicitStepStats {
  ImplicitSolver solver = ImplicitSolver::cg;  // the one used (never automatic)
  int iterations = 0;                          // PCG iterations
  bool factorized = false;                     // the direct path refactored this step
  int eliminated = 0;                          // coordinates eliminated by rails
  int schurRows = 0;                           // constraint rows through the Schur complement
};

struct ImplicitScratch {
  ForceJacobians jacobians;
  std::vector<ConstraintRow> constraintRows;
  ConstraintRowsJ rows;
  AssemblyPattern pattern;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<char> pinned, found, railed;
  std::vector<int> allRows, generalRows, railRows;  // constraint rows by how the solve takes them
  Eigen::SparseMatrix<double> matrix;
  Eigen::VectorXd k1, rhs, dv, known;  // k1: dy/dt at the start; known: eliminated coordinates' Δv
  std::vector<double> pairA, pairKu;  // per Jacobian pair: −η d − η² k (xx, xy, yy), k (x̄ − x_b + η (v_a − v_b))
  JacobiPreconditioner jacobi;
  LdltPreconditioner ldlt;
  bool ldltValid = false;  // factors (of an earlier or this step's A) of the current pattern
  bool autoDirect = false;              // auto has moved to the direct solve
  std::vector<int> cgIterationsWindow;  // auto: the last kAutoWindow CG steps' iterations
  double reuseDebt = 0.0;  // multiply-adds the stale factors' extra iterations have cost
  long factorizations = 0;
  ProjectedPcgScratch pcg;
  ImplicitStepStats stats;
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

// One step by h: y holds the state the step is linearised at, taken at time t, and receives the
// step's end. Throws ImplicitSolverError when the scene's implicit solver is
// `direct` and more constraint rows than kMaxSchurRows are neither fixed points nor rails.
void implicitStep(System& system, Eigen::VectorXd& y, double t, double h, const ImplicitTarget& target,
                  ImplicitScratch& w, double cgTolerance = kCgTolerance);

}  // namespace particles
