#pragma once
// Jacobi: G = diag(A), G⁻¹ = 0 on pinned coordinates (a fixed particle's, whose Δv is 0). Cheap
// to form and to apply (one multiply per coordinate), and S = J G⁻¹ Jᵀ stays as sparse as J Jᵀ;
// but CG's iterations grow like √cond(G⁻¹A), about h √(k/m) on a cloth of springs k and masses
// m: the stiffer the springs, the more iterations, as an explicit integrator's step count grows.

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

#include "core/projected_pcg.hpp"

namespace particles {

class JacobiPreconditioner : public PcgPreconditioner {
 public:
  // G from A's diagonal; pinned[i] != 0 leaves coordinate i out.
  void setMatrix(WorkerPool* pool, const Eigen::SparseMatrix<double>& a, const std::vector<char>& pinned);

  void prepareRows(ConstraintRowsJ& rows) override;
  void apply(WorkerPool* pool, const Eigen::VectorXd& r, Eigen::VectorXd& g) override;
  void solveSchur(const Eigen::VectorXd& rhs, Eigen::VectorXd& lambda) override { lambda = ldlt_.solve(rhs); }
  void subtractPreconditionedJt(const ConstraintRowsJ& rows, const Eigen::VectorXd& lambda,
                                Eigen::VectorXd& z) override {
    rows.subtractTransposed(lambda, z, &dinv_);
  }
  // g = G⁻¹ r again on the coordinates J touches (the others did not change).
  void refreshAfterCorrection(const ConstraintRowsJ& rows, const Eigen::VectorXd& lambda, const Eigen::VectorXd& r,
                              Eigen::VectorXd& g) override;

 private:
  Eigen::VectorXd dinv_;
  std::vector<Eigen::Triplet<double>> triplets_;
  Eigen::SparseMatrix<double> j_, s_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
};

}  // namespace particles
