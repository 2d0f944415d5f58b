#include "core/constraint_solver.hpp"

namespace particles {

template <class Precond>
void ConstraintSolver::runCg(ConstraintSolveStats& stats) {
  // A local solver: it keeps a reference to a_, which must not outlive a move of this object.
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper, Precond> cg;
  if (options_.maxIterations > 0) cg.setMaxIterations(options_.maxIterations);
  cg.setTolerance(options_.tolerance);
  cg.compute(a_);
  lambda_ = cg.solveWithGuess(rhs_, lambda_);
  stats.iterations = int(cg.iterations());
  stats.relativeResidual = cg.error();
}

Preconditioner ConstraintSolver::automaticPreconditioner(const Model& model) {
  // Particles are nodes, a row touching two moving particles an edge; a row with one moving
  // particle (a bead, a rod to a fixed point) only couples rows at that particle, which a loop-free
  // structure tolerates. An edge between two particles already connected closes a loop. The
  // union-find runs over the compact columns (columnOf_ still set), so its cost is per row, not
  // per particle of the system.
  parent_.resize(touched_.size());
  for (size_t i = 0; i < parent_.size(); ++i) parent_[i] = int(i);
  auto root = [this](int c) {
    while (parent_[size_t(c)] != c) c = parent_[size_t(c)] = parent_[size_t(parent_[size_t(c)])];
    return c;
  };
  int edges = 0;
  for (const ConstraintRow& row : rows_) {
    if (row.count < 2 || model.isFixed(row.particle[0]) || model.isFixed(row.particle[1])) continue;
    const int a = root(columnOf_[size_t(row.particle[0])]), b = root(columnOf_[size_t(row.particle[1])]);
    if (a == b) return Preconditioner::jacobi;  // a loop
    parent_[size_t(a)] = b;
    ++edges;
  }
  // No edge at all (rails, beads): J W Jᵀ is diagonal or nearly so, and the diagonal is exact or
  // close while its setup costs half as much.
  return edges > 0 ? Preconditioner::incompleteCholesky : Preconditioner::jacobi;
}

ConstraintSolveStats ConstraintSolver::solve(const Model& model, const StateView& s, const ConstraintList& constraints,
                                             ForceAccumulator& acc) {
  const int m = int(constraints.size());
  ConstraintSolveStats stats;
  stats.rows = m;
  if (m == 0) return stats;
  if (columnOf_.size() != size_t(model.layout.numParticles)) columnOf_.assign(size_t(model.layout.numParticles), -1);
  touched_.clear();

  rows_.resize(size_t(m));
  rhs_.resize(m);
  jwTriplets_.clear();
  jTriplets_.clear();
  diagTriplets_.clear();
  std::vector<double> diag(size_t(m), 0.0);
  double diagSum = 0.0;
  for (int i = 0; i < m; ++i) {
    const Constraint& c = *constraints[size_t(i)];
    ConstraintRow& row = rows_[size_t(i)] = c.evaluate(s);
    double jdotQdot = 0.0, jwq = 0.0;
    for (int k = 0; k < row.count; ++k) {
      const int p = row.particle[size_t(k)];
      const Vec2& jk = row.J[size_t(k)];
      const double w = model.invMass[p];
      jdotQdot += row.Jdot[size_t(k)].dot(s.vel(p));
      jwq += w * jk.dot(acc.forceOn(p));
      diag[size_t(i)] += w * jk.squaredNorm();
      int& column = columnOf_[size_t(p)];
      if (column < 0) {
        column = int(touched_.size());
        touched_.push_back(p);
      }
      for (int d = 0; d < 2; ++d) {
        jTriplets_.emplace_back(i, 2 * column + d, jk[d]);
        if (w != 0.0) jwTriplets_.emplace_back(i, 2 * column + d, w * jk[d]);
      }
    }
    rhs_[i] = -jdotQdot - jwq - c.feedback().ks * row.C - c.feedback().kd * row.Cdot;
    diagSum += diag[size_t(i)];
  }

  const double epsilon = options_.regularization * diagSum / m;
  for (int i = 0; i < m; ++i) {
    if (diag[size_t(i)] == 0.0) {
      // Only fixed particles: nothing can move, so no force is needed.
      diagTriplets_.emplace_back(i, i, 1.0);
      rhs_[i] = 0.0;
    } else {
      diagTriplets_.emplace_back(i, i, epsilon);
    }
  }

  Preconditioner preconditioner = options_.preconditioner;
  if (preconditioner == Preconditioner::automatic) preconditioner = automaticPreconditioner(model);
  stats.preconditioner = preconditioner;

  const int cols = 2 * int(touched_.size());
  for (int p : touched_) columnOf_[size_t(p)] = -1;
  jw_.resize(m, cols);
  jw_.setFromTriplets(jwTriplets_.begin(), jwTriplets_.end());
  j_.resize(m, cols);
  j_.setFromTriplets(jTriplets_.begin(), jTriplets_.end());
  Eigen::SparseMatrix<double> regularizer(m, m);
  regularizer.setFromTriplets(diagTriplets_.begin(), diagTriplets_.end());
  a_ = Eigen::SparseMatrix<double>(jw_ * j_.transpose()) + regularizer;

  if (lambda_.size() != m) lambda_.setZero(m);
  if (preconditioner == Preconditioner::incompleteCholesky) {
    runCg<Eigen::IncompleteCholesky<double>>(stats);
  } else {
    runCg<Eigen::DiagonalPreconditioner<double>>(stats);
  }

  // Q̂ = Jᵀ λ
  for (int i = 0; i < m; ++i) {
    const ConstraintRow& row = rows_[size_t(i)];
    for (int k = 0; k < row.count; ++k) acc.addForce(row.particle[size_t(k)], lambda_[i] * row.J[size_t(k)]);
  }
  return stats;
}

}  // namespace particles
