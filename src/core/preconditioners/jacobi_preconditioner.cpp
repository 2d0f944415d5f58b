#include "core/preconditioners/jacobi_preconditioner.hpp"

namespace particles {

void JacobiPreconditioner::setMatrix(WorkerPool* pool, const Eigen::SparseMatrix<double>& a,
                                     const std::vector<char>& pinned) {
  const Eigen::Index n = a.rows();
  dinv_.resize(n);
  forSegments(pool, n, [&](long first, long count) {
    for (Eigen::Index i = first; i < first + count; ++i) dinv_[i] = pinned[size_t(i)] ? 0.0 : 1.0 / a.coeff(i, i);
  });
}

void JacobiPreconditioner::prepareRows(ConstraintRowsJ& rows) {
  const int m = rows.size();
  if (m == 0) return;
  triplets_.clear();
  for (int r = 0; r < m; ++r) {
    for (int k = 0; k < 4; ++k) {
      const int col = rows.columns[size_t(r)][size_t(k)];
      if (col >= 0) triplets_.emplace_back(r, col, rows.values[size_t(r)][size_t(k)]);
    }
  }
  j_.resize(m, dinv_.size());
  j_.setFromTriplets(triplets_.begin(), triplets_.end());
  s_ = j_ * dinv_.asDiagonal() * j_.transpose();
  // Redundant rows make S singular: ε of its mean diagonal keeps it factorable, as in the
  // multiplier solve (the loop's second projection pass removes what ε leaves of J g).
  const double mean = s_.diagonal().sum() / m;
  for (int r = 0; r < m; ++r) {
    if (s_.coeff(r, r) == 0.0) {
      s_.coeffRef(r, r) = 1.0;
      rows.c[r] = 0.0;
    } else {
      s_.coeffRef(r, r) += 1e-12 * mean;
    }
  }
  ldlt_.compute(s_);
}

void JacobiPreconditioner::apply(WorkerPool* pool, const Eigen::VectorXd& r, Eigen::VectorXd& g) {
  g.resize(r.size());
  forSegments(pool, r.size(),
              [&](long i, long len) { g.segment(i, len) = dinv_.segment(i, len).cwiseProduct(r.segment(i, len)); });
}

void JacobiPreconditioner::refreshAfterCorrection(const ConstraintRowsJ& rows, const Eigen::VectorXd&,
                                                  const Eigen::VectorXd& r, Eigen::VectorXd& g) {
  for (const auto& columns : rows.columns) {
    for (int col : columns) {
      if (col >= 0) g[col] = dinv_[col] * r[col];
    }
  }
}

}  // namespace particles
