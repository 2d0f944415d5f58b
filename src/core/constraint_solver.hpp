#pragma once
// Lagrange-multiplier constraint forces (docs/physics.md §5, Witkin & Baraff "Constrained dynamics"):
//   J W Jᵀ λ = −J̇ q̇ − J W Q − k_s C − k_d Ċ,     Q̂ = Jᵀ λ
// q are the particles' positions, W their inverse masses and Q the forces accumulated so far.
// J W Jᵀ is assembled as an Eigen sparse matrix and solved by conjugate gradients, warm-started
// from the previous λ (between two evaluations the multipliers change little).
// Preconditioner, chosen per solve by default (Preconditioner::automatic):
//  - where rows join moving particles without closing a loop (chains, curtains of chains, trees
//    of rods), an incomplete Cholesky factor (Eigen::IncompleteCholesky, no fill-in
//    beyond J W Jᵀ's own pattern). The exact factor has no fill-in either there, so one CG step
//    solves the system: a 10,000-rod chain that diagonal preconditioning needs 9,999 iterations
//    for (O(R²)) takes one (timings in bench/README.md, "One constraint solve");
//  - otherwise the diagonal (Jacobi): with loops (nets) incomplete Cholesky needed more
//    iterations and more time (bench/README.md, "One constraint solve"); with no row joining two moving
//    particles (rails, beads) J W Jᵀ is (nearly) diagonal and Jacobi's setup is cheaper.
// Incomplete Cholesky runs in Eigen's ConjugateGradient (its triangular solves are sequential);
// Jacobi in our own loop, the same algorithm as Eigen's, whose products and dot products run on
// the System's threads in an order that does not depend on their number (core/parallel_sparse.hpp).
// Q̂ = Jᵀλ and the projections' moves are gathered per particle, its rows in row order: the
// additions a loop over the rows makes, on the threads.
//
// J W Jᵀ is only positive semi-definite. Two cases make it singular and are handled:
//  - a row that touches only fixed particles (W = 0) has an all-zero row; it gets λ = 0;
//  - redundant rows (two constraints on one degree of freedom) make it rank deficient; a small
//    Tikhonov term ε·mean(diag) on the diagonal keeps λ finite even when their right-hand sides
//    disagree. Its effect on consistent systems is a relative 1e-10, far below CG's tolerance.

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "core/constraint.hpp"
#include "core/force_accumulator.hpp"
#include "core/model.hpp"
#include "core/worker_pool.hpp"

namespace particles {

enum class Preconditioner {
  automatic,  // incomplete Cholesky when the rows form no loop, else Jacobi (see above)
  incompleteCholesky,
  jacobi,
};

struct ConstraintSolverOptions {
  Preconditioner preconditioner = Preconditioner::automatic;
  double tolerance = 1e-10;       // CG stops at |r| ≤ tolerance·|b|
  int maxIterations = 0;          // 0: Eigen's default, twice the number of rows
  double regularization = 1e-10;  // ε above, relative to the mean diagonal
};

struct ConstraintSolveStats {
  int rows = 0;
  Preconditioner preconditioner = Preconditioner::jacobi;  // the one used: never automatic
  int iterations = 0;
  double relativeResidual = 0.0;
};

using ConstraintList = std::vector<std::unique_ptr<Constraint>>;

class ConstraintSolver {
 public:
  explicit ConstraintSolver(ConstraintSolverOptions options = {}) : options_(options) {}
  // The System's threads, for the per-row work (evaluating rows, the right-hand side), Jacobi CG
  // and the per-particle sums; null: serial.
  void setPool(WorkerPool* pool) { pool_ = pool; }
  // Adds the constraint force Q̂ = Jᵀλ to acc (which must already hold every other force).
  ConstraintSolveStats solve(const Model& model, const StateView& s, const ConstraintList& constraints,
                             ForceAccumulator& acc);
  const Eigen::VectorXd& lambda() const { return lambda_; }
  // The multipliers the next solve starts from, and putting them back: an evaluation made only to
  // look at the state (System::draw's accelerations) must leave the next step's start as it was.
  Eigen::VectorXd warmStart() const { return lambda_; }
  void restoreWarmStart(Eigen::VectorXd lambda) { lambda_ = std::move(lambda); }

  // For integrators that keep constraints by projection rather than by the multipliers' forces
  // (symplectic Euler, Verlet, backward Euler: docs/physics.md §3). Each moves y along W Jᵀ (the
  // mass-weighted closest point; Cline & Pai 2003's post-stabilisation):
  //   positions   (J W Jᵀ) μ = −C,   q ← q + W Jᵀ μ   Newton steps until every violation ≤ 1e-12 m (≤ 4)
  //   velocities  (J W Jᵀ) μ = −J q̇, q̇ ← q̇ + W Jᵀ μ  once (Ċ = J q̇ is linear in q̇)
  // projectVelocities uses J at y's positions as they are; project does positions, then velocities.
  void projectPositions(const Model& model, Eigen::VectorXd& y, const ConstraintList& constraints);
  void projectVelocities(const Model& model, Eigen::VectorXd& y, const ConstraintList& constraints);
  void project(const Model& model, Eigen::VectorXd& y, const ConstraintList& constraints) {
    projectPositions(model, y, constraints);
    projectVelocities(model, y, constraints);
  }

 private:
  // Evaluates every row at s and assembles J W Jᵀ (plus ε on the diagonal, and 1 for rows that
  // touch only fixed particles, whose inert_ flag is then set) into a_, J into j_, W J into jw_.
  void assemble(const Model& model, const StateView& s, const ConstraintList& constraints);
  // Solves a_ x = rhs_ by CG from the guess in x, with the preconditioner chosen as above.
  template <class Precond>
  void runCg(Eigen::VectorXd& x, ConstraintSolveStats& stats);
  // Jacobi-preconditioned CG on the threads: Eigen's algorithm and stopping rule.
  void runJacobiCg(Eigen::VectorXd& x, ConstraintSolveStats& stats);
  // body(p, row, k) for every row entry k touching particle p, particles (the compact columns) in
  // chunks on the threads, each particle's entries in row order.
  template <class Body>
  void forEachParticleEntry(Body&& body) const;
  void solveAssembled(const Model& model, Eigen::VectorXd& x, ConstraintSolveStats& stats);
  // y[offset + 2p …] += W_p Jᵀ μ for every row's particles: the move of a projection.
  void moveAlongRows(const Model& model, Eigen::VectorXd& y, Eigen::Index offset) const;
  // Incomplete Cholesky when rows join moving particles and no row closes a loop among them
  // (rows meeting only at fixed particles do not couple in J W Jᵀ), else Jacobi. Needs rows_
  // and the compact columns of the solve in progress.
  Preconditioner automaticPreconditioner(const Model& model);

  ConstraintSolverOptions options_;
  WorkerPool* pool_ = nullptr;
  std::vector<ConstraintRow> rows_;
  // Compact column numbering: only particles some constraint touches get columns, so a few
  // constraints on a large cloth cost per constraint, not per particle.
  std::vector<int> columnOf_;  // per particle: compact column block, or -1
  std::vector<int> touched_;
  bool diagonal_ = false;       // no moving particle in two rows: J W Jᵀ + εI is aDiagonal_
  Eigen::VectorXd aDiagonal_;
  std::vector<int> parent_;  // union-find over compact columns, for automaticPreconditioner
  // Per compact column c (particle touched_[c]): its row entries 2·row + k, in row order, at
  // columnEntries_[columnStart_[c] … columnStart_[c + 1]).
  std::vector<int> columnOfEntry_, columnStart_, columnEntries_;
  std::vector<Eigen::Triplet<double>> jwTriplets_, jTriplets_, diagTriplets_;
  std::vector<double> diag_;
  std::vector<char> inert_;  // per row: touches only fixed particles
  Eigen::SparseMatrix<double> jw_, j_, a_;
  Eigen::VectorXd rhs_, lambda_, mu_;
  Eigen::VectorXd residual_, direction_, product_, preconditioned_, inverseDiagonal_;  // Jacobi CG
  std::vector<double> partials_;
};

}  // namespace particles
