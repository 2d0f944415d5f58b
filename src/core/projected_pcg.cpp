#include "core/projected_pcg.hpp"

#include <cmath>

#include "core/parallel_sparse.hpp"

namespace particles {

void ConstraintRowsJ::multiply(const Eigen::VectorXd& z, Eigen::VectorXd& out) const {
  const int m = size();
  out.resize(m);
  for (int r = 0; r < m; ++r) {
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
      const int col = columns[size_t(r)][size_t(k)];
      if (col >= 0) sum += values[size_t(r)][size_t(k)] * z[col];
    }
    out[r] = sum;
  }
}

void ConstraintRowsJ::subtractTransposed(const Eigen::VectorXd& lambda, Eigen::VectorXd& z,
                                         const Eigen::VectorXd* scale) const {
  for (int r = 0; r < size(); ++r) {
    for (int k = 0; k < 4; ++k) {
      const int col = columns[size_t(r)][size_t(k)];
      if (col >= 0) z[col] -= (scale ? (*scale)[col] : 1.0) * values[size_t(r)][size_t(k)] * lambda[r];
    }
  }
}

ProjectedPcgResult solveProjectedPcg(WorkerPool* pool, const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b,
                                     const ConstraintRowsJ& rows, PcgPreconditioner& pre, Eigen::VectorXd& x,
                                     double tolerance, int maxIterations, ProjectedPcgScratch& w, PcgStart start) {
  const Eigen::Index n = b.size();
  const int m = rows.size();
  // r ← r − Jᵀ S⁻¹ J G⁻¹ r, twice, keeping g = G⁻¹ r: g = P r with r kept small (see the header).
  auto project = [&](Eigen::VectorXd& r, Eigen::VectorXd& g) {
    pre.apply(pool, r, g);
    for (int pass = 0; m > 0 && pass < 2; ++pass) {
      rows.multiply(g, w.jz);
      pre.solveSchur(w.jz, w.lambda);
      rows.subtractTransposed(w.lambda, r);
      pre.refreshAfterCorrection(rows, w.lambda, r, g);
    }
  };
  // z ← z − G⁻¹ Jᵀ S⁻¹ (J z − c), twice: onto J z = c.
  auto feasible = [&](Eigen::VectorXd& z) {
    for (int pass = 0; m > 0 && pass < 2; ++pass) {
      rows.multiply(z, w.jz);
      w.jz -= rows.c;
      pre.solveSchur(w.jz, w.lambda);
      pre.subtractPreconditionedJt(rows, w.lambda, z);
    }
  };

  // The products, dot products and updates below are split over the threads: A x by columns,
  // dot products in fixed chunks, the rest elementwise.
  auto dot = [&](const Eigen::VectorXd& u, const Eigen::VectorXd& v) { return dotChunks(pool, u, v, w.partials); };
  w.r = b;
  project(w.r, w.g);
  const double reference = std::abs(dot(w.r, w.g));  // ‖b‖² in P's metric: the stopping scale
  if (start != PcgStart::guess) {
    x = w.g;
  } else if (x.size() != n) {
    x.setZero(n);
  }
  feasible(x);
  ProjectedPcgResult result;
  if (start == PcgStart::exact) {
    result.converged = true;  // G is A: P b, on J x = c, is the answer (see the header)
    return result;
  }
  multiplySymmetric(pool, a, x, w.r);
  forSegments(pool, n, [&](long i, long len) { w.r.segment(i, len) -= b.segment(i, len); });
  project(w.r, w.g);
  w.p.resize(n);
  forSegments(pool, n, [&](long i, long len) { w.p.segment(i, len) = -w.g.segment(i, len); });
  double rg = dot(w.r, w.g);
  auto converged = [&] { return std::abs(rg) <= tolerance * tolerance * reference; };
  while (result.iterations < maxIterations && !converged()) {
    multiplySymmetric(pool, a, w.p, w.ap);
    const double alpha = rg / dot(w.p, w.ap);
    forSegments(pool, n, [&](long i, long len) {
      x.segment(i, len) += alpha * w.p.segment(i, len);
      w.r.segment(i, len) += alpha * w.ap.segment(i, len);
    });
    ++result.iterations;
    project(w.r, w.g);
    const double rgNext = dot(w.r, w.g);
    const double beta = rgNext / rg;
    forSegments(pool, n,
                [&](long i, long len) { w.p.segment(i, len) = -w.g.segment(i, len) + beta * w.p.segment(i, len); });
    rg = rgNext;
  }
  result.converged = converged();
  feasible(x);  // what rounding left of J x − c
  return result;
}

}  // namespace particles
