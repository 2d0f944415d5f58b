#include "core/preconditioners/ldlt_preconditioner.hpp"

namespace particles {

void LdltPreconditioner::analyze(const Eigen::SparseMatrix<double>& a) {
  ldlt_.analyze(a);
  factorCost_ = iterationCost_ = 0.0;
}

bool LdltPreconditioner::factorize(const Eigen::SparseMatrix<double>& a) {
  if (!ldlt_.factorize(a)) return false;
  factorCost_ = ldlt_.factorMultiplyAdds();
  iterationCost_ = ldlt_.solveMultiplyAdds() + double(a.nonZeros()) + 10.0 * double(a.rows());
  return true;
}

void LdltPreconditioner::apply(WorkerPool*, const Eigen::VectorXd& r, Eigen::VectorXd& g) {
  ldlt_.solve(r, g);
}

void LdltPreconditioner::prepareRows(ConstraintRowsJ& rows) {
  const int m = rows.size();
  if (m == 0) return;
  const Eigen::Index n = ldlt_.rows();
  jt_.setZero(n, m);
  for (int r = 0; r < m; ++r) {
    for (int k = 0; k < 4; ++k) {
      const int col = rows.columns[size_t(r)][size_t(k)];
      if (col >= 0) jt_(col, r) += rows.values[size_t(r)][size_t(k)];
    }
  }
  ginvJt_.resize(n, m);
  Eigen::VectorXd column;
  for (int r = 0; r < m; ++r) {
    ldlt_.solve(jt_.col(r), column);
    ginvJt_.col(r) = column;
  }
  s_ = jt_.transpose() * ginvJt_;
  // As Jacobi's S: a row with nothing free is dropped; ε keeps redundant rows factorable.
  const double mean = s_.diagonal().sum() / m;
  for (int r = 0; r < m; ++r) {
    if (s_(r, r) == 0.0) {
      s_(r, r) = 1.0;
      rows.c[r] = 0.0;
    } else {
      s_(r, r) += 1e-12 * mean;
    }
  }
  schur_.compute(s_);
}

void LdltPreconditioner::subtractPreconditionedJt(const ConstraintRowsJ&, const Eigen::VectorXd& lambda,
                                                  Eigen::VectorXd& z) {
  z.noalias() -= ginvJt_ * lambda;
}

}  // namespace particles
