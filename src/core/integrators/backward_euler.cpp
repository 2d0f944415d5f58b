#include "core/integrators/backward_euler.hpp"

#include <algorithm>
#include <cmath>

#include "core/group_by_bucket.hpp"
#include "core/parallel_sparse.hpp"
#include "core/system.hpp"

namespace particles {

namespace {

struct ProjectedCgStats {
  int iterations = 0;
};

// Projected preconditioned conjugate gradients (Gould, Hribar & Nocedal 2001; Baraff & Witkin
// 1998 §5.3's "filter" is its one-particle case): solves A x = b over the x with J x = c, where
// J's rows are the constraints'. The preconditioned residual is projected onto J's null space,
//   g = P r,   P = D⁻¹ − D⁻¹ Jᵀ (J D⁻¹ Jᵀ)⁻¹ J D⁻¹,   D = diag(A) (0 for fixed coordinates),
// with S = J D⁻¹ Jᵀ (one row per constraint) factored once by sparse LDLᵀ. At the solution r is
// not zero but Jᵀλ (λ: the constraint impulses), and it grows while g shrinks; computed plainly,
// P r then loses J g = 0 to rounding and the iterates drift off J x = c, step after step, to the
// unconstrained answer (seen: a 25-particle chain on a rail fell freely). Gould et al.'s residual
// update keeps r small instead: r ← r − Jᵀ S⁻¹ J D⁻¹ r (twice, the second refining the first),
// then g = D⁻¹ r. Without constraints this is Jacobi-preconditioned CG. Eigen's
// ConjugateGradient takes no such projection, hence this loop.
ProjectedCgStats solveProjectedCg(WorkerPool* pool, const Model& model, const Eigen::SparseMatrix<double>& a,
                                  const Eigen::VectorXd& b, const std::vector<ConstraintRow>& rows,
                                  const Eigen::VectorXd& v0, Eigen::VectorXd& x, double tolerance,
                                  ProjectedCgScratch& w) {
  const Eigen::Index n = b.size();
  const int m = int(rows.size());
  w.dinv.resize(n);
  forSegments(pool, n, [&](long first, long count) {
    for (Eigen::Index i = first; i < first + count; ++i) {
      w.dinv[i] = model.invMass[i / 2] == 0.0 ? 0.0 : 1.0 / a.coeff(i, i);
    }
  });

  // J (m × n) and c = −J v₀; a row on fixed particles only cannot be met by any Δv and is dropped.
  // J is kept twice: sparse, to form S once, and row by row, for the products in the loop (each
  // touches at most four coordinates, so projecting costs O(m), not O(n)).
  w.triplets.clear();
  w.c.setZero(m);
  w.rowColumns.assign(size_t(m), {-1, -1, -1, -1});
  w.rowValues.assign(size_t(m), {0.0, 0.0, 0.0, 0.0});
  for (int r = 0; r < m; ++r) {
    const ConstraintRow& row = rows[size_t(r)];
    for (int k = 0; k < row.count; ++k) {
      const int p = row.particle[size_t(k)];
      for (int d = 0; d < 2; ++d) {
        const double value = row.J[size_t(k)][d];
        w.triplets.emplace_back(r, 2 * p + d, value);
        w.rowColumns[size_t(r)][size_t(2 * k + d)] = 2 * p + d;
        w.rowValues[size_t(r)][size_t(2 * k + d)] = value;
        w.c[r] -= value * v0[2 * p + d];
      }
    }
  }
  w.j.resize(m, n);
  w.j.setFromTriplets(w.triplets.begin(), w.triplets.end());
  if (m > 0) {
    w.s = w.j * w.dinv.asDiagonal() * w.j.transpose();
    // Redundant rows make S singular: ε of its mean diagonal keeps it factorable, as in the
    // multiplier solve (the refinement below removes what ε leaves of J g); a row with nothing
    // free gets 1 and c = 0.
    const double mean = w.s.diagonal().sum() / m;
    for (int r = 0; r < m; ++r) {
      if (w.s.coeff(r, r) == 0.0) {
        w.s.coeffRef(r, r) = 1.0;
        w.c[r] = 0.0;
      } else {
        w.s.coeffRef(r, r) += 1e-12 * mean;
      }
    }
    w.ldlt.compute(w.s);
  }
  auto multiplyJ = [&](const Eigen::VectorXd& z, Eigen::VectorXd& out) {
    out.resize(m);
    for (int r = 0; r < m; ++r) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) {
        const int col = w.rowColumns[size_t(r)][size_t(k)];
        if (col >= 0) sum += w.rowValues[size_t(r)][size_t(k)] * z[col];
      }
      out[r] = sum;
    }
  };
  // z −= scale ⊙ Jᵀ λ, on the coordinates J touches only; scale is 1 or D⁻¹.
  auto subtractJt = [&](const Eigen::VectorXd& lambda, Eigen::VectorXd& z, bool scaleByDinv) {
    for (int r = 0; r < m; ++r) {
      for (int k = 0; k < 4; ++k) {
        const int col = w.rowColumns[size_t(r)][size_t(k)];
        if (col >= 0) z[col] -= (scaleByDinv ? w.dinv[col] : 1.0) * w.rowValues[size_t(r)][size_t(k)] * lambda[r];
      }
    }
  };
  // r ← r − Jᵀ S⁻¹ J D⁻¹ r, twice; then g = D⁻¹ r = P r with r kept small (see above).
  auto project = [&](Eigen::VectorXd& r, Eigen::VectorXd& g) {
    g.resize(n);
    forSegments(pool, n,
                [&](long i, long len) { g.segment(i, len) = w.dinv.segment(i, len).cwiseProduct(r.segment(i, len)); });
    for (int pass = 0; m > 0 && pass < 2; ++pass) {
      multiplyJ(g, w.jz);
      w.lambda = w.ldlt.solve(w.jz);
      subtractJt(w.lambda, r, false);
      for (int row = 0; row < m; ++row) {
        for (int k = 0; k < 4; ++k) {
          const int col = w.rowColumns[size_t(row)][size_t(k)];
          if (col >= 0) g[col] = w.dinv[col] * r[col];
        }
      }
    }
  };
  // z ← z − D⁻¹ Jᵀ S⁻¹ (J z − c), twice: onto J z = c.
  auto feasible = [&](Eigen::VectorXd& z) {
    for (int pass = 0; m > 0 && pass < 2; ++pass) {
      multiplyJ(z, w.jz);
      w.jz -= w.c;
      w.lambda = w.ldlt.solve(w.jz);
      subtractJt(w.lambda, z, true);
    }
  };

  if (x.size() != n) x.setZero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (w.dinv[i] == 0.0) x[i] = 0.0;
  }
  feasible(x);  // from the last step's Δv
  // The products, dot products and updates below are split over the threads: A x by columns,
  // dot products in fixed chunks, the rest elementwise.
  auto dot = [&](const Eigen::VectorXd& u, const Eigen::VectorXd& v) { return dotChunks(pool, u, v, w.partials); };
  w.r = b;
  project(w.r, w.g);
  const double reference = std::abs(dot(w.r, w.g));  // ‖b‖² in P's metric: the stopping scale
  multiplySymmetric(pool, a, x, w.r);
  forSegments(pool, n, [&](long i, long len) { w.r.segment(i, len) -= b.segment(i, len); });
  project(w.r, w.g);
  w.p.resize(n);
  forSegments(pool, n, [&](long i, long len) { w.p.segment(i, len) = -w.g.segment(i, len); });
  double rg = dot(w.r, w.g);
  ProjectedCgStats stats;
  const int maxIterations = int(std::max<Eigen::Index>(2 * n, 10));
  while (stats.iterations < maxIterations && std::abs(rg) > tolerance * tolerance * reference) {
    multiplySymmetric(pool, a, w.p, w.ap);
    const double alpha = rg / dot(w.p, w.ap);
    forSegments(pool, n, [&](long i, long len) {
      x.segment(i, len) += alpha * w.p.segment(i, len);
      w.r.segment(i, len) += alpha * w.ap.segment(i, len);
    });
    project(w.r, w.g);
    const double rgNext = dot(w.r, w.g);
    const double beta = rgNext / rg;
    forSegments(pool, n,
                [&](long i, long len) { w.p.segment(i, len) = -w.g.segment(i, len) + beta * w.p.segment(i, len); });
    rg = rgNext;
    ++stats.iterations;
  }
  feasible(x);  // what rounding left of J x − c
  return stats;
}

}  // namespace

void integrateBackwardEuler(System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w,
                            const BackwardEulerOptions& options) {
  const Model& model = system.model();
  const StateLayout& layout = model.layout;
  const Eigen::Index n = 2 * Eigen::Index(layout.numPoints());
  const Eigen::Index vOff = layout.velocityOffset();

  system.derivEval(y, t, w.k1, System::ConstraintForces::skip);  // [v₀ | f₀/m | ω₀ | τ₀/I]
  system.forceJacobians(y, t, w.jacobians);
  auto fixedDof = [&](Eigen::Index i) { return model.invMass[i / 2] == 0.0; };

  // A = M − h D − h² K over the free coordinates; a fixed one's row and column are the identity.
  // The Jacobians' pattern only changes when a contact or a mouse spring starts or ends, so A's
  // pattern is built once and its values are scattered into it while the triplets' (row, column)
  // sequence is the one it was built from (a full setFromTriplets costs several times more).
  const ForceJacobians& jac = w.jacobians;
  AssemblyPattern& pattern = w.pattern;
  WorkerPool* pool = system.pool();
  auto samePattern = [&](const ForceJacobians::Triplets& from, const std::vector<int>& keys) {
    if (2 * from.size() != keys.size()) return false;
    return !anyOf(pool, from.size(), kRowChunk, w.cg.found,
                  [&](size_t k) { return from[k].row() != keys[2 * k] || from[k].col() != keys[2 * k + 1]; });
  };
  if (!pattern.valid || w.matrix.rows() != n || !samePattern(jac.dfdv, pattern.dfdvKeys) ||
      !samePattern(jac.dfdx, pattern.dfdxKeys)) {
    w.triplets.clear();
    w.triplets.reserve(size_t(n) + jac.dfdv.size() + jac.dfdx.size());
    for (Eigen::Index i = 0; i < n; ++i) w.triplets.emplace_back(i, i, 1.0);
    auto keysOf = [&](const ForceJacobians::Triplets& from, std::vector<int>& keys) {
      keys.clear();
      for (const auto& e : from) {
        keys.push_back(e.row());
        keys.push_back(e.col());
        if (!fixedDof(e.row()) && !fixedDof(e.col())) w.triplets.emplace_back(e.row(), e.col(), 1.0);
      }
    };
    keysOf(jac.dfdv, pattern.dfdvKeys);
    keysOf(jac.dfdx, pattern.dfdxKeys);
    w.matrix.resize(n, n);
    w.matrix.setFromTriplets(w.triplets.begin(), w.triplets.end());
    w.matrix.makeCompressed();
    // Where entry (row, col) sits in A's value array (columns are sorted: compressed storage).
    auto slotOf = [&](Eigen::Index row, Eigen::Index col) -> int {
      const int* inner = w.matrix.innerIndexPtr();
      const int* begin = inner + w.matrix.outerIndexPtr()[col];
      const int* end = inner + w.matrix.outerIndexPtr()[col + 1];
      return int(std::lower_bound(begin, end, int(row)) - inner);
    };
    // Each Jacobian entry's slot (−1: a fixed coordinate's, left out).
    auto slotsOf = [&](const ForceJacobians::Triplets& from, std::vector<int>& slots) {
      slots.clear();
      for (const auto& e : from) slots.push_back(fixedDof(e.row()) || fixedDof(e.col()) ? -1 : slotOf(e.row(), e.col()));
    };
    std::vector<int> slotOfEntry, dfdxSlots;
    slotsOf(jac.dfdv, slotOfEntry);
    slotsOf(jac.dfdx, dfdxSlots);
    slotOfEntry.insert(slotOfEntry.end(), dfdxSlots.begin(), dfdxSlots.end());
    // The reverse maps (see AssemblyPattern), by counting sorts that keep the triplets' order.
    const size_t slots = size_t(w.matrix.nonZeros());
    pattern.slotDiagonal.assign(slots, -1);
    for (Eigen::Index i = 0; i < n; ++i) pattern.slotDiagonal[size_t(slotOf(i, i))] = int(i);
    groupByBucket(slots, slotOfEntry, pattern.slotStart, pattern.slotEntries);
    std::vector<int> rowOfEntry;
    rowOfEntry.reserve(jac.dfdx.size());
    for (const auto& e : jac.dfdx) rowOfEntry.push_back(int(e.row()));
    groupByBucket(size_t(n), rowOfEntry, pattern.kRowStart, pattern.kRowEntries);
    pattern.valid = true;
  }
  // A's values, slot by slot: the diagonal's M (1 for a fixed coordinate), then −h D and −h² K in
  // the triplets' order.
  double* values = w.matrix.valuePtr();
  const int dCount = int(jac.dfdv.size());
  forChunks(pool, size_t(w.matrix.nonZeros()), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t slot = begin; slot < end; ++slot) {
      const int diagonal = pattern.slotDiagonal[slot];
      double value = diagonal < 0 ? 0.0 : (fixedDof(diagonal) ? 1.0 : model.mass[diagonal / 2]);
      for (int k = pattern.slotStart[slot]; k < pattern.slotStart[slot + 1]; ++k) {
        const int entry = pattern.slotEntries[size_t(k)];
        value +=
            entry < dCount ? -h * jac.dfdv[size_t(entry)].value() : (-h * h) * jac.dfdx[size_t(entry - dCount)].value();
      }
      values[slot] = value;
    }
  });

  // b = h (f₀ + h K v₀), row by row; K v₀ straight from K's triplets, in their order.
  w.rhs.resize(n);
  forChunks(pool, size_t(n), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      double value = model.mass[Eigen::Index(i / 2)] * w.k1[vOff + Eigen::Index(i)];
      for (int k = pattern.kRowStart[i]; k < pattern.kRowStart[i + 1]; ++k) {
        const auto& e = jac.dfdx[size_t(pattern.kRowEntries[size_t(k)])];
        value += h * e.value() * y[vOff + e.col()];
      }
      w.rhs[Eigen::Index(i)] = fixedDof(Eigen::Index(i)) ? 0.0 : h * value;
    }
  });

  // Δv with J Δv = −J v₀, so that v₁ keeps every constraint's Ċ = 0 (J at x₀).
  w.constraintRows.clear();
  const StateView s0(layout, y);
  for (const auto& c : system.constraints()) w.constraintRows.push_back(c->evaluate(s0));
  ProjectedCgStats stats = solveProjectedCg(pool, model, w.matrix, w.rhs, w.constraintRows, y.segment(vOff, n), w.dv,
                                            options.tolerance, w.cg);
  w.cgIterations = stats.iterations;

  forSegments(pool, n, [&](long i, long len) {
    y.segment(vOff + i, len) += w.dv.segment(i, len);
    y.segment(i, len) += h * y.segment(vOff + i, len);
  });
  // Rotation: explicit (see the header).
  const int bodies = layout.numBodies;
  y.segment(layout.omegaOffset(), bodies) += h * w.k1.segment(layout.omegaOffset(), bodies);
  y.segment(layout.angleOffset(), bodies) += h * y.segment(layout.omegaOffset(), bodies);
}

}  // namespace particles
