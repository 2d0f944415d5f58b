#pragma once
// The direct solve: G = L D Lᵀ, a sparse LDLᵀ factorisation of A over the particles' 2 × 2 blocks
// (core/block_ldlt.hpp, approximate-minimum-degree ordering), so that G⁻¹ r costs two sparse
// triangular solves.
//
// The ordering and the elimination tree (the symbolic analysis) depend only on A's pattern and
// are computed once per pattern (analyze); the numbers are refactored (factorize) when the
// owner decides (core/implicit_step.cpp: when the iterations that stale factors cost have added
// up to a factorisation). With A's own factors the projected PCG ends after one iteration; with
// an earlier step's, after a few: G⁻¹A is then close to the identity whatever the stiffness, which
// is why this path does not slow down as springs stiffen, unlike Jacobi.
//
// Constraint rows that were not eliminated (core/implicit_step.cpp keeps fixed points and
// axis-aligned rails out of A) go through the Schur complement S = J G⁻¹ Jᵀ: G⁻¹ Jᵀ by one solve
// per row, kept dense (n × rows), and S dense (rows × rows) with a pivoting LDLᵀ, so this is for a
// few rows (kMaxSchurRows), not a net of thousands of rods.
//
// Why our own factorisation rather than Eigen's SimplicialLDLT or CHOLMOD's (simplicial LDLᵀ,
// supernodal LLᵀ): supernodes are small on a cloth's grid, so CHOLMOD does not pay; the 2 × 2
// blocks do (core/block_ldlt.hpp says why). The timings of all four on the 25² and 100² cloths'
// A: bench/README.md, "Block LDLᵀ".

#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "core/block_ldlt.hpp"
#include "core/projected_pcg.hpp"

namespace particles {

// Rows the Schur complement takes; past this, the direct solve is not offered (CG is).
constexpr int kMaxSchurRows = 64;

class LdltPreconditioner : public PcgPreconditioner {
 public:
  // The symbolic analysis of A's pattern (ordering, elimination tree).
  void analyze(const Eigen::SparseMatrix<double>& a);
  // The numbers; false when A is not factorable (a zero pivot: A is not positive definite).
  bool factorize(const Eigen::SparseMatrix<double>& a);
  // Floating-point multiply-adds of one factorisation and of one PCG iteration (two triangular
  // solves and A's product): what decides when to refactor. Known after the first factorize.
  double factorCost() const { return factorCost_; }
  double iterationCost() const { return iterationCost_; }

  void prepareRows(ConstraintRowsJ& rows) override;
  void apply(WorkerPool* pool, const Eigen::VectorXd& r, Eigen::VectorXd& g) override;
  void solveSchur(const Eigen::VectorXd& rhs, Eigen::VectorXd& lambda) override { lambda = schur_.solve(rhs); }
  void subtractPreconditionedJt(const ConstraintRowsJ& rows, const Eigen::VectorXd& lambda,
                                Eigen::VectorXd& z) override;

 private:
  BlockLdlt ldlt_;
  double factorCost_ = 0.0, iterationCost_ = 0.0;
  Eigen::MatrixXd jt_, ginvJt_, s_;  // Jᵀ, G⁻¹ Jᵀ (n × rows), S (rows × rows)
  Eigen::LDLT<Eigen::MatrixXd> schur_;
};

}  // namespace particles
