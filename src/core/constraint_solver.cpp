#include "core/constraint_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/group_by_bucket.hpp"
#include "core/parallel_sparse.hpp"

namespace particles {

namespace {
constexpr size_t kConstraintRowChunk = 4096;  // rows (or touched particles) per chunk of the loops
}

template <class Precond>
void ConstraintSolver::runCg(Eigen::VectorXd& x, ConstraintSolveStats& stats) {
  // A local solver: it keeps a reference to a_, which must not outlive a move of this object.
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper, Precond> cg;
  if (options_.maxIterations > 0) cg.setMaxIterations(options_.maxIterations);
  cg.setTolerance(options_.tolerance);
  cg.compute(a_);
  x = cg.solveWithGuess(rhs_, x);
  stats.iterations = int(cg.iterations());
  stats.relativeResidual = cg.error();
}

void ConstraintSolver::runJacobiCg(Eigen::VectorXd& x, ConstraintSolveStats& stats) {
  const Eigen::Index n = a_.cols();
  auto dot = [&](const Eigen::VectorXd& u, const Eigen::VectorXd& v) { return dotChunks(pool_, u, v, partials_); };
  // Eigen's DiagonalPreconditioner: 1/A_ii, or 1 where A_ii is 0.
  inverseDiagonal_ = a_.diagonal();
  for (double& d : inverseDiagonal_) d = d != 0.0 ? 1.0 / d : 1.0;
  const int maxIterations = options_.maxIterations > 0 ? options_.maxIterations : int(2 * n);

  multiplySymmetric(pool_, a_, x, product_);
  residual_.resize(n);
  forSegments(pool_, n, [&](long i, long m) { residual_.segment(i, m) = rhs_.segment(i, m) - product_.segment(i, m); });
  const double rhsNorm2 = dot(rhs_, rhs_);
  if (rhsNorm2 == 0.0) {
    x.setZero();
    stats.iterations = 0;
    stats.relativeResidual = 0.0;
    return;
  }
  const double threshold =
      std::max(options_.tolerance * options_.tolerance * rhsNorm2, std::numeric_limits<double>::min());
  double residualNorm2 = dot(residual_, residual_);
  int iteration = 0;
  if (residualNorm2 >= threshold) {
    direction_.resize(n);
    preconditioned_.resize(n);
    forSegments(pool_, n, [&](long i, long m) {
      direction_.segment(i, m) = residual_.segment(i, m).cwiseProduct(inverseDiagonal_.segment(i, m));
    });
    double absNew = dot(residual_, direction_);
    while (iteration < maxIterations) {
      multiplySymmetric(pool_, a_, direction_, product_);
      const double alpha = absNew / dot(direction_, product_);
      forSegments(pool_, n, [&](long i, long m) {
        x.segment(i, m) += alpha * direction_.segment(i, m);
        residual_.segment(i, m) -= alpha * product_.segment(i, m);
      });
      residualNorm2 = dot(residual_, residual_);
      if (residualNorm2 < threshold) break;
      forSegments(pool_, n, [&](long i, long m) {
        preconditioned_.segment(i, m) = residual_.segment(i, m).cwiseProduct(inverseDiagonal_.segment(i, m));
      });
      const double absOld = absNew;
      absNew = dot(residual_, preconditioned_);
      const double beta = absNew / absOld;
      forSegments(pool_, n, [&](long i, long m) {
        direction_.segment(i, m) = preconditioned_.segment(i, m) + beta * direction_.segment(i, m);
      });
      ++iteration;
    }
  }
  stats.iterations = iteration;
  stats.relativeResidual = std::sqrt(residualNorm2 / rhsNorm2);
}

template <class Body>
void ConstraintSolver::forEachParticleEntry(Body&& body) const {
  forChunks(pool_, touched_.size(), kConstraintRowChunk, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c) {
      const int p = touched_[c];
      for (int e = columnStart_[c]; e < columnStart_[c + 1]; ++e) {
        const int entry = columnEntries_[size_t(e)];
        body(p, size_t(entry / 2), size_t(entry % 2));
      }
    }
  });
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

void ConstraintSolver::assemble(const Model& model, const StateView& s, const ConstraintList& constraints) {
  const int m = int(constraints.size());
  if (columnOf_.size() != size_t(model.layout.numParticles)) columnOf_.assign(size_t(model.layout.numParticles), -1);
  touched_.clear();
  rows_.resize(size_t(m));
  jwTriplets_.clear();
  jTriplets_.clear();
  diagTriplets_.clear();
  diag_.assign(size_t(m), 0.0);
  inert_.assign(size_t(m), 0);
  double diagSum = 0.0;
  // Each row on its own (threads take chunks of rows); the compact columns below are numbered in
  // row order, so that part stays on one thread.
  forChunks(pool_, size_t(m), kConstraintRowChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) rows_[i] = constraints[i]->evaluate(s);
  });
  // The compact columns, each row's diagonal entry of J W Jᵀ, and whether any moving particle is
  // in two rows: when none is, J W Jᵀ is diagonal (a rail's or a set of beads' rows, each on a
  // particle of its own), and the solve is one division per row, without the sparse matrices.
  diagonal_ = true;
  for (int i = 0; i < m; ++i) {
    ConstraintRow& row = rows_[size_t(i)];
    for (int k = 0; k < row.count; ++k) {
      const int p = row.particle[size_t(k)];
      const double w = model.invMass[p];
      diag_[size_t(i)] += w * row.J[size_t(k)].squaredNorm();
      int& column = columnOf_[size_t(p)];
      if (column < 0) {
        column = int(touched_.size());
        touched_.push_back(p);
      } else if (w != 0.0) {
        diagonal_ = false;  // a second entry on a moving particle, in this row or another
      }
    }
    diagSum += diag_[size_t(i)];
  }
  columnOfEntry_.assign(2 * size_t(m), -1);
  for (int i = 0; i < m; ++i) {
    const ConstraintRow& row = rows_[size_t(i)];
    for (int k = 0; k < row.count; ++k)
      columnOfEntry_[2 * size_t(i) + size_t(k)] = columnOf_[size_t(row.particle[size_t(k)])];
  }
  groupByBucket(touched_.size(), columnOfEntry_, columnStart_, columnEntries_);

  const double epsilon = options_.regularization * diagSum / m;
  aDiagonal_.resize(m);
  for (int i = 0; i < m; ++i) {
    // Only fixed particles: nothing can move, so no force is needed.
    inert_[size_t(i)] = diag_[size_t(i)] == 0.0;
    aDiagonal_[i] = inert_[size_t(i)] ? 1.0 : diag_[size_t(i)] + epsilon;
  }
  if (diagonal_) return;

  for (int i = 0; i < m; ++i) {
    const ConstraintRow& row = rows_[size_t(i)];
    for (int k = 0; k < row.count; ++k) {
      const int p = row.particle[size_t(k)];
      const Vec2& jk = row.J[size_t(k)];
      const double w = model.invMass[p];
      const int column = columnOf_[size_t(p)];
      for (int d = 0; d < 2; ++d) {
        jTriplets_.emplace_back(i, 2 * column + d, jk[d]);
        if (w != 0.0) jwTriplets_.emplace_back(i, 2 * column + d, w * jk[d]);
      }
    }
    diagTriplets_.emplace_back(i, i, inert_[size_t(i)] ? 1.0 : epsilon);
  }

  const int cols = 2 * int(touched_.size());
  jw_.resize(m, cols);
  jw_.setFromTriplets(jwTriplets_.begin(), jwTriplets_.end());
  j_.resize(m, cols);
  j_.setFromTriplets(jTriplets_.begin(), jTriplets_.end());
  Eigen::SparseMatrix<double> regularizer(m, m);
  regularizer.setFromTriplets(diagTriplets_.begin(), diagTriplets_.end());
  a_ = Eigen::SparseMatrix<double>(jw_ * j_.transpose()) + regularizer;
}

void ConstraintSolver::solveAssembled(const Model& model, Eigen::VectorXd& x, ConstraintSolveStats& stats) {
  // automaticPreconditioner reads the compact columns, which are cleared here for the next call.
  Preconditioner preconditioner = options_.preconditioner;
  if (preconditioner == Preconditioner::automatic) preconditioner = automaticPreconditioner(model);
  for (int p : touched_) columnOf_[size_t(p)] = -1;
  stats.preconditioner = preconditioner;
  for (Eigen::Index i = 0; i < rhs_.size(); ++i) {
    if (inert_[size_t(i)]) rhs_[i] = 0.0;
  }
  if (diagonal_) {
    // J W Jᵀ + εI is diagonal: the exact solution, which Jacobi-preconditioned CG reaches in its
    // first step (to rounding).
    stats.preconditioner = Preconditioner::jacobi;
    x = rhs_.cwiseQuotient(aDiagonal_);
    stats.iterations = 1;
    stats.relativeResidual = 0.0;
    return;
  }
  if (x.size() != rhs_.size()) x.setZero(rhs_.size());
  if (preconditioner == Preconditioner::incompleteCholesky) {
    runCg<Eigen::IncompleteCholesky<double>>(x, stats);
  } else {
    runJacobiCg(x, stats);
  }
}

ConstraintSolveStats ConstraintSolver::solve(const Model& model, const StateView& s, const ConstraintList& constraints,
                                             ForceAccumulator& acc) {
  const int m = int(constraints.size());
  ConstraintSolveStats stats;
  stats.rows = m;
  if (m == 0) return stats;
  assemble(model, s, constraints);
  rhs_.resize(m);
  forChunks(pool_, size_t(m), kConstraintRowChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const ConstraintRow& row = rows_[i];
      double jdotQdot = 0.0, jwq = 0.0;
      for (int k = 0; k < row.count; ++k) {
        const int p = row.particle[size_t(k)];
        jdotQdot += row.Jdot[size_t(k)].dot(s.vel(p));
        jwq += model.invMass[p] * row.J[size_t(k)].dot(acc.forceOn(p));
      }
      const ConstraintFeedback& feedback = constraints[i]->feedback();
      rhs_[Eigen::Index(i)] = -jdotQdot - jwq - feedback.ks * row.C - feedback.kd * row.Cdot;
    }
  });
  solveAssembled(model, lambda_, stats);

  // Q̂ = Jᵀ λ
  forEachParticleEntry([&](int p, size_t i, size_t k) { acc.addForce(p, lambda_[Eigen::Index(i)] * rows_[i].J[k]); });
  return stats;
}

void ConstraintSolver::moveAlongRows(const Model& model, Eigen::VectorXd& y, Eigen::Index offset) const {
  forEachParticleEntry([&](int p, size_t i, size_t k) {
    const Vec2 dq = model.invMass[p] * mu_[Eigen::Index(i)] * rows_[i].J[k];
    y[offset + 2 * p] += dq.x();
    y[offset + 2 * p + 1] += dq.y();
  });
}

void ConstraintSolver::projectPositions(const Model& model, Eigen::VectorXd& y, const ConstraintList& constraints) {
  const int m = int(constraints.size());
  if (m == 0) return;
  constexpr int kMaxNewtonSteps = 4;
  constexpr double kPositionTolerance = 1e-12;  // m
  ConstraintSolveStats stats;
  for (int step = 0; step < kMaxNewtonSteps; ++step) {
    const StateView s(model.layout, y);
    double worst = 0.0;
    for (const auto& c : constraints) worst = std::max(worst, c->violation(s));
    if (worst <= kPositionTolerance) break;
    assemble(model, s, constraints);
    rhs_.resize(m);
    for (int i = 0; i < m; ++i) rhs_[i] = -rows_[size_t(i)].C;
    mu_.setZero(m);
    solveAssembled(model, mu_, stats);
    moveAlongRows(model, y, 0);
  }
}

void ConstraintSolver::projectVelocities(const Model& model, Eigen::VectorXd& y, const ConstraintList& constraints) {
  const int m = int(constraints.size());
  if (m == 0) return;
  ConstraintSolveStats stats;
  assemble(model, StateView(model.layout, y), constraints);
  rhs_.resize(m);
  for (int i = 0; i < m; ++i) rhs_[i] = -rows_[size_t(i)].Cdot;
  mu_.setZero(m);
  solveAssembled(model, mu_, stats);
  moveAlongRows(model, y, model.layout.velocityOffset());
}

}  // namespace particles
