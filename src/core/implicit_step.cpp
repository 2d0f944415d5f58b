#include "core/implicit_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/group_by_bucket.hpp"
#include "core/parallel_sparse.hpp"
#include "core/system.hpp"

namespace particles {

namespace {

// A constraint row that fixes one coordinate by itself: one particle, J with one non-zero
// component (a horizontal line's J = (0, 1)). Returns that coordinate, or −1.
int axisAlignedCoordinate(const ConstraintRow& row) {
  if (row.count != 1) return -1;
  const Vec2& j = row.J[0];
  if (j.x() != 0.0 && j.y() == 0.0) return 2 * row.particle[0];
  if (j.x() == 0.0 && j.y() != 0.0) return 2 * row.particle[0] + 1;
  return -1;
}

// The constraint rows for the solve, J Δv = c with c = −J v₀. CG keeps every row and every
// column (a pinned coordinate's G⁻¹ is 0). The direct path leaves out the eliminated rows, and
// the pinned columns, whose known Δv moves into c.
void gatherRows(const std::vector<ConstraintRow>& from, const std::vector<int>& keep,
                const Eigen::Ref<const Eigen::VectorXd>& v0, const std::vector<char>* pinned,
                const Eigen::VectorXd* known, ConstraintRowsJ& to) {
  const int m = int(keep.size());
  to.columns.assign(size_t(m), {-1, -1, -1, -1});
  to.values.assign(size_t(m), {0.0, 0.0, 0.0, 0.0});
  to.c.setZero(m);
  for (int r = 0; r < m; ++r) {
    const ConstraintRow& row = from[size_t(keep[size_t(r)])];
    for (int k = 0; k < row.count; ++k) {
      for (int d = 0; d < 2; ++d) {
        const int col = 2 * row.particle[size_t(k)] + d;
        const double value = row.J[size_t(k)][d];
        to.c[r] -= value * v0[col];
        if (pinned && (*pinned)[size_t(col)]) {
          to.c[r] -= value * (*known)[col];
          continue;
        }
        to.columns[size_t(r)][size_t(2 * k + d)] = col;
        to.values[size_t(r)][size_t(2 * k + d)] = value;
      }
    }
  }
}

}  // namespace

double autoDirectIterations(long freeCoordinates) {
  return 14.0 * std::pow(double(std::max(freeCoordinates, 1L)) / 1250.0, 0.3);
}

void implicitStep(System& system, Eigen::VectorXd& y, double t, double h, const ImplicitTarget& target,
                  ImplicitScratch& w, double cgTolerance) {
  const Model& model = system.model();
  const StateLayout& layout = model.layout;
  const Eigen::Index n = 2 * Eigen::Index(layout.numPoints());
  const Eigen::Index vOff = layout.velocityOffset();
  const double eta = target.eta;
  WorkerPool* pool = system.pool();

  system.derivEval(y, t, w.k1, System::ConstraintForces::skip);  // [v₀ | f₀/m | ω₀ | τ₀/I]
  system.forceJacobians(y, t, w.jacobians);
  w.constraintRows.clear();
  const StateView s0(layout, y);
  for (const auto& c : system.constraints()) w.constraintRows.push_back(c->evaluate(s0));

  // Which solve: the direct one eliminates axis-aligned rails and takes the other rows through
  // its Schur complement, so it needs those to be few.
  auto fixedDof = [&](Eigen::Index i) { return model.invMass[i / 2] == 0.0; };
  w.pinned.assign(size_t(n), 0);
  for (Eigen::Index i = 0; i < n; ++i) w.pinned[size_t(i)] = fixedDof(i) ? 1 : 0;
  w.known.setZero(n);
  std::vector<int>&all = w.allRows, &general = w.generalRows, &eliminable = w.railRows;
  all.clear();
  general.clear();
  eliminable.clear();
  int eliminated = 0;
  std::vector<char>& railed = w.railed;
  railed.assign(size_t(n), 0);
  for (size_t r = 0; r < w.constraintRows.size(); ++r) {
    all.push_back(int(r));
    const ConstraintRow& row = w.constraintRows[r];
    bool touchesFree = false;
    for (int k = 0; k < row.count; ++k) touchesFree = touchesFree || model.invMass[row.particle[size_t(k)]] != 0.0;
    if (!touchesFree) continue;  // nothing can meet it: dropped
    const int coordinate = axisAlignedCoordinate(row);
    if (coordinate >= 0 && !railed[size_t(coordinate)]) {
      railed[size_t(coordinate)] = 1;
      eliminable.push_back(int(r));
      ++eliminated;
    } else {
      general.push_back(int(r));
    }
  }
  const long freeCoordinates = long(std::count(w.pinned.begin(), w.pinned.end(), 0)) - eliminated;
  const ImplicitSolver requested = system.implicitSolver();
  const bool automatic = requested == ImplicitSolver::automatic;
  ImplicitSolver solver = requested;
  if (automatic) {
    solver = w.autoDirect && int(general.size()) <= kMaxSchurRows ? ImplicitSolver::direct : ImplicitSolver::cg;
  }
  if (solver == ImplicitSolver::direct && int(general.size()) > kMaxSchurRows) {
    throw ImplicitSolverError(fmt::format(
        "implicit_solver: direct: {} constraint rows are neither fixed points nor axis-aligned rails, and the direct "
        "solve takes at most {} such rows (their Schur complement is dense); use implicit_solver: cg or auto",
        general.size(), kMaxSchurRows));
  }
  const bool direct = solver == ImplicitSolver::direct && n > 0;
  if (direct) {
    for (int r : eliminable) {
      const ConstraintRow& row = w.constraintRows[size_t(r)];
      const int coordinate = axisAlignedCoordinate(row);
      // J_i Δv_i = c = −J_i v₀ᵢ: the rail's coordinate ends the step at rest (Ċ = 0).
      w.known[coordinate] = -y[vOff + coordinate];
      w.pinned[size_t(coordinate)] = 1;
    }
  }

  // A = M − η D − η² K over the free coordinates; a pinned one's row and column are the identity.
  // The Jacobians' pattern only changes when a contact or a mouse spring starts or ends, so A's
  // pattern is built once and its values are scattered into it while the triplets' (row, column)
  // sequence is the one it was built from (a full setFromTriplets costs several times more).
  const ForceJacobians& jac = w.jacobians;
  AssemblyPattern& pattern = w.pattern;
  auto pinned = [&](Eigen::Index i) { return w.pinned[size_t(i)] != 0; };
  auto samePattern = [&](const ForceJacobians::Triplets& from, const std::vector<int>& keys) {
    if (2 * from.size() != keys.size()) return false;
    return !anyOf(pool, from.size(), kRowChunk, w.found,
                  [&](size_t k) { return ((from[k].row() ^ keys[2 * k]) | (from[k].col() ^ keys[2 * k + 1])) != 0; });
  };
  const ForceJacobians::Pairs& pairs = jac.pairs;
  auto samePairs = [&] {
    if (2 * pairs.size() != pattern.pairKeys.size()) return false;
    return !anyOf(pool, pairs.size(), kRowChunk, w.found, [&](size_t q) {
      return ((pairs[q].a ^ pattern.pairKeys[2 * q]) | (pairs[q].b ^ pattern.pairKeys[2 * q + 1])) != 0;
    });
  };
  // Pair q's block `role` (AssemblyPattern): its row and column points, and its sign.
  auto blockPoints = [&](int q, int role) {
    const JacobianPair& pair = pairs[size_t(q)];
    const int rowPoint = role == 0 || role == 2 ? pair.a : pair.b;
    const int colPoint = role == 0 || role == 3 ? pair.a : pair.b;
    return std::pair{rowPoint, colPoint};
  };
  const bool rebuild = !pattern.valid || w.matrix.rows() != n || pattern.pinned != w.pinned ||
                       !samePattern(jac.dfdv, pattern.dfdvKeys) || !samePattern(jac.dfdx, pattern.dfdxKeys) ||
                       !samePairs();
  if (rebuild) {
    w.triplets.clear();
    w.triplets.reserve(size_t(n) + jac.dfdv.size() + jac.dfdx.size() + 16 * pairs.size());
    for (Eigen::Index i = 0; i < n; ++i) w.triplets.emplace_back(i, i, 1.0);
    pattern.pairKeys.clear();
    for (int q = 0; q < int(pairs.size()); ++q) {
      pattern.pairKeys.push_back(pairs[size_t(q)].a);
      pattern.pairKeys.push_back(pairs[size_t(q)].b);
      for (int role = 0; role < 4; ++role) {
        const auto [rowPoint, colPoint] = blockPoints(q, role);
        for (int c = 0; c < 2; ++c) {
          for (int r = 0; r < 2; ++r) {
            const int row = 2 * rowPoint + r, col = 2 * colPoint + c;
            if (!pinned(row) && !pinned(col)) w.triplets.emplace_back(row, col, 1.0);
          }
        }
      }
    }
    auto keysOf = [&](const ForceJacobians::Triplets& from, std::vector<int>& keys) {
      keys.clear();
      for (const auto& e : from) {
        keys.push_back(e.row());
        keys.push_back(e.col());
        if (!pinned(e.row()) && !pinned(e.col())) w.triplets.emplace_back(e.row(), e.col(), 1.0);
      }
    };
    keysOf(jac.dfdv, pattern.dfdvKeys);
    keysOf(jac.dfdx, pattern.dfdxKeys);
    pattern.pinned = w.pinned;
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
    // Each Jacobian entry's slot (−1: a pinned coordinate's, left out).
    std::vector<int> slotOfEntry;
    slotOfEntry.reserve(jac.dfdv.size() + jac.dfdx.size());
    pattern.pinnedColumnEntries.clear();
    auto slotsOf = [&](const ForceJacobians::Triplets& from, int firstEntry) {
      for (size_t k = 0; k < from.size(); ++k) {
        const auto& e = from[k];
        const bool out = pinned(e.row()) || pinned(e.col());
        slotOfEntry.push_back(out ? -1 : slotOf(e.row(), e.col()));
        if (!pinned(e.row()) && pinned(e.col()) && !fixedDof(e.col())) {
          pattern.pinnedColumnEntries.push_back(firstEntry + int(k));
        }
      }
    };
    slotsOf(jac.dfdv, 0);
    slotsOf(jac.dfdx, int(jac.dfdv.size()));
    // The reverse maps (see AssemblyPattern), by counting sorts that keep the triplets' order.
    const size_t slots = size_t(w.matrix.nonZeros());
    pattern.slotDiagonal.assign(slots, -1);
    for (Eigen::Index i = 0; i < n; ++i) pattern.slotDiagonal[size_t(slotOf(i, i))] = int(i);
    groupByBucket(slots, slotOfEntry, pattern.slotStart, pattern.slotEntries);
    std::vector<int> rowOfEntry;
    rowOfEntry.reserve(jac.dfdx.size());
    for (const auto& e : jac.dfdx) rowOfEntry.push_back(int(e.row()));
    groupByBucket(size_t(n), rowOfEntry, pattern.kRowStart, pattern.kRowEntries);
    // The pairs' blocks of A, each found by its first slot that is not pinned out.
    auto slotsOfBlock = [&](int ref, int* slot) {
      const auto [rowPoint, colPoint] = blockPoints(ref / 4, ref % 4);
      for (int c = 0; c < 2; ++c) {
        for (int r = 0; r < 2; ++r) {
          const int row = 2 * rowPoint + r, col = 2 * colPoint + c;
          slot[r + 2 * c] = pinned(row) || pinned(col) ? -1 : slotOf(row, col);
        }
      }
    };
    std::vector<int> leadSlotOfRef(4 * pairs.size(), -1), blockStart, blockRefs;
    pattern.pinnedPairEntries.clear();
    for (int ref = 0; ref < int(leadSlotOfRef.size()); ++ref) {
      int slot[4];
      slotsOfBlock(ref, slot);
      for (int s : slot) {
        if (s >= 0) {
          leadSlotOfRef[size_t(ref)] = s;
          break;
        }
      }
      const auto [rowPoint, colPoint] = blockPoints(ref / 4, ref % 4);
      for (int c = 0; c < 2; ++c) {
        for (int r = 0; r < 2; ++r) {
          const int row = 2 * rowPoint + r, col = 2 * colPoint + c;
          if (!pinned(row) && pinned(col) && !fixedDof(col)) pattern.pinnedPairEntries.push_back({ref, r, c});
        }
      }
    }
    groupByBucket(slots, leadSlotOfRef, blockStart, pattern.pairBlockRefs);
    pattern.pairBlocks.clear();
    for (size_t slot = 0; slot < slots; ++slot) {
      if (blockStart[slot + 1] == blockStart[slot]) continue;
      AssemblyPattern::PairBlock block{};
      slotsOfBlock(pattern.pairBlockRefs[size_t(blockStart[slot])], block.slot);
      block.begin = blockStart[slot];
      block.end = blockStart[slot + 1];
      pattern.pairBlocks.push_back(block);
    }
    std::vector<int> pointOfRef(2 * pairs.size());
    for (size_t q = 0; q < pairs.size(); ++q) {
      pointOfRef[2 * q] = pairs[q].a;
      pointOfRef[2 * q + 1] = pairs[q].b;
    }
    groupByBucket(size_t(n / 2), pointOfRef, pattern.pairPointStart, pattern.pairPointRefs);
    pattern.valid = true;
    w.ldltValid = false;
  }
  // A's values, slot by slot: the diagonal's M (1 for a pinned coordinate), then −η D and −η² K in
  // the triplets' order.
  double* values = w.matrix.valuePtr();
  const int dCount = int(jac.dfdv.size());
  auto entryValue = [&](int entry) {
    return entry < dCount ? -eta * jac.dfdv[size_t(entry)].value()
                          : (-eta * eta) * jac.dfdx[size_t(entry - dCount)].value();
  };
  forChunks(pool, size_t(w.matrix.nonZeros()), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t slot = begin; slot < end; ++slot) {
      const int diagonal = pattern.slotDiagonal[slot];
      double value = diagonal < 0 ? 0.0 : (pinned(diagonal) ? 1.0 : model.mass[diagonal / 2]);
      for (int k = pattern.slotStart[slot]; k < pattern.slotStart[slot + 1]; ++k)
        value += entryValue(pattern.slotEntries[size_t(k)]);
      values[slot] = value;
    }
  });
  // The pairs' part, block by block: A's (a, a) and (b, b) blocks gain −η d − η² k, (a, b) and
  // (b, a) lose it.
  std::vector<double>& pairA = w.pairA;
  pairA.resize(3 * pairs.size());
  forChunks(pool, pairs.size(), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t q = begin; q < end; ++q) {
      for (int j = 0; j < 3; ++j) pairA[3 * q + size_t(j)] = -eta * pairs[q].d[j] - eta * eta * pairs[q].k[j];
    }
  });
  forChunks(pool, pattern.pairBlocks.size(), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      const AssemblyPattern::PairBlock& block = pattern.pairBlocks[b];
      double sum[3] = {0.0, 0.0, 0.0};
      for (int k = block.begin; k < block.end; ++k) {
        const int ref = pattern.pairBlockRefs[size_t(k)];
        const double* m = &pairA[3 * size_t(ref / 4)];
        const double sign = ref % 4 < 2 ? 1.0 : -1.0;
        for (int j = 0; j < 3; ++j) sum[j] += sign * m[j];
      }
      const double entry[4] = {sum[0], sum[1], sum[1], sum[2]};  // xx, yx, xy, yy
      for (int j = 0; j < 4; ++j) {
        if (block.slot[j] >= 0) values[block.slot[j]] += entry[j];
      }
    }
  });

  // b = M (v̄ − v₀) + η (f₀ + K (x̄ − x₀ + η v₀)), row by row; K's products straight from its
  // triplets, in their order.
  const Eigen::VectorXd* xShift = target.xShift;
  const Eigen::VectorXd* vShift = target.vShift;
  // A pair's K times that vector is k (u_a − u_b) at a and its negative at b.
  std::vector<double>& pairKu = w.pairKu;
  pairKu.resize(2 * pairs.size());
  forChunks(pool, pairs.size(), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t q = begin; q < end; ++q) {
      const int a = pairs[q].a, b = pairs[q].b;
      double u[2];
      for (int d = 0; d < 2; ++d) {
        u[d] = eta * (y[vOff + 2 * a + d] - y[vOff + 2 * b + d]);
        if (xShift) u[d] += (*xShift)[2 * a + d] - (*xShift)[2 * b + d];
      }
      const double* k = pairs[q].k;
      pairKu[2 * q] = k[0] * u[0] + k[1] * u[1];
      pairKu[2 * q + 1] = k[1] * u[0] + k[2] * u[1];
    }
  });
  w.rhs.resize(n);
  forChunks(pool, size_t(n), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const double mass = model.mass[Eigen::Index(i / 2)];
      double value = mass * w.k1[vOff + Eigen::Index(i)];
      for (int k = pattern.kRowStart[i]; k < pattern.kRowStart[i + 1]; ++k) {
        const auto& e = jac.dfdx[size_t(pattern.kRowEntries[size_t(k)])];
        value += eta * e.value() * y[vOff + e.col()];
        if (xShift) value += e.value() * (*xShift)[e.col()];
      }
      for (int k = pattern.pairPointStart[i / 2]; k < pattern.pairPointStart[i / 2 + 1]; ++k) {
        const int ref = pattern.pairPointRefs[size_t(k)];
        const double ku = pairKu[2 * size_t(ref / 2) + i % 2];
        value += ref % 2 == 0 ? ku : -ku;
      }
      double b = eta * value;
      if (vShift) b += mass * (*vShift)[Eigen::Index(i)];
      w.rhs[Eigen::Index(i)] = pinned(Eigen::Index(i)) ? 0.0 : b;
    }
  });
  // The eliminated coordinates' known Δv times their columns of A leaves the free rows' side.
  for (int entry : pattern.pinnedColumnEntries) {
    const auto& e = entry < dCount ? jac.dfdv[size_t(entry)] : jac.dfdx[size_t(entry - dCount)];
    w.rhs[e.row()] -= entryValue(entry) * w.known[e.col()];
  }
  for (const auto& [ref, r, c] : pattern.pinnedPairEntries) {
    const auto [rowPoint, colPoint] = blockPoints(ref / 4, ref % 4);
    const double* m = &pairA[3 * size_t(ref / 4)];
    const double entry = (ref % 4 < 2 ? 1.0 : -1.0) * m[r + c];  // xx, xy = yx, yy
    w.rhs[2 * rowPoint + r] -= entry * w.known[2 * colPoint + c];
  }

  // Δv with J Δv = −J v₀, so that v₁ keeps every constraint's Ċ = 0 (J at x₀).
  const Eigen::Ref<const Eigen::VectorXd> v0 = y.segment(vOff, n);
  if (w.dv.size() != n) w.dv.setZero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (pinned(i)) w.dv[i] = 0.0;  // the last step's Δv is the first guess
  }
  ImplicitStepStats& stats = w.stats;
  stats = {};
  stats.eliminated = direct ? eliminated : 0;
  auto solveByCg = [&] {
    gatherRows(w.constraintRows, all, v0, nullptr, nullptr, w.rows);
    w.jacobi.setMatrix(pool, w.matrix, w.pinned);
    w.jacobi.prepareRows(w.rows);
    const int maxIterations = int(std::max<Eigen::Index>(2 * n, 10));
    stats.solver = ImplicitSolver::cg;
    stats.schurRows = 0;
    stats.iterations =
        solveProjectedPcg(pool, w.matrix, w.rhs, w.rows, w.jacobi, w.dv, cgTolerance, maxIterations, w.pcg).iterations;
  };
  if (!direct) {
    solveByCg();
    // auto: CG steps dearer than the direct solve at this size, on average, move the run to it.
    if (automatic && int(general.size()) <= kMaxSchurRows) {
      std::vector<int>& window = w.cgIterationsWindow;
      if (int(window.size()) == kAutoWindow) window.erase(window.begin());
      window.push_back(stats.iterations);
      const double mean = double(std::accumulate(window.begin(), window.end(), 0)) / double(window.size());
      if (int(window.size()) == kAutoWindow && mean > autoDirectIterations(freeCoordinates)) w.autoDirect = true;
    }
  } else {
    gatherRows(w.constraintRows, general, v0, &w.pinned, &w.known, w.rows);
    stats.solver = ImplicitSolver::direct;
    stats.schurRows = w.rows.size();
    auto refactor = [&] {
      if (!w.ldltValid) w.ldlt.analyze(w.matrix);
      w.ldltValid = w.ldlt.factorize(w.matrix);
      w.reuseDebt = 0.0;
      stats.factorized = true;
      ++w.factorizations;
      return w.ldltValid;
    };
    // Refactor when the stale factors' extra iterations have cost as much as a factorisation
    // (the rent-or-buy rule: never more than twice the cheaper of the two choices in hindsight).
    bool ok = w.ldltValid && w.reuseDebt < w.ldlt.factorCost() ? true : refactor();
    if (ok) {
      w.ldlt.prepareRows(w.rows);
      // A's own factors give the answer in one solve; an earlier step's iterate from there.
      ProjectedPcgResult r =
          solveProjectedPcg(pool, w.matrix, w.rhs, w.rows, w.ldlt, w.dv, kDirectTolerance, kMaxReuseIterations, w.pcg,
                            stats.factorized ? PcgStart::exact : PcgStart::preconditioned);
      stats.iterations = r.iterations;
      if (!r.converged && !stats.factorized) {
        // Factors too far from A to converge soon: A's own, and on from here.
        ok = refactor();
        if (ok) {
          w.ldlt.prepareRows(w.rows);
          r = solveProjectedPcg(pool, w.matrix, w.rhs, w.rows, w.ldlt, w.dv, kDirectTolerance, kMaxReuseIterations,
                                w.pcg, PcgStart::exact);
          stats.iterations += r.iterations;
        }
      }
      // What reuse cost beyond A's own factors' one solve: the residual's check and the iterations.
      if (ok && !stats.factorized) w.reuseDebt += double(r.iterations + 1) * w.ldlt.iterationCost();
    }
    if (!ok) {
      // Not positive definite (cannot happen with the forces' negative semi-definite blocks; a
      // guard): this step by CG, which needs no factors.
      w.ldltValid = false;
      solveByCg();
    } else {
      w.dv += w.known;
    }
  }

  const bool bdf = xShift != nullptr;
  forSegments(pool, n, [&](long i, long len) {
    y.segment(vOff + i, len) += w.dv.segment(i, len);
    if (bdf) y.segment(i, len) += xShift->segment(i, len);
    y.segment(i, len) += eta * y.segment(vOff + i, len);
  });
  // Rotation: explicit (see the header).
  const int bodies = layout.numBodies;
  if (target.rotationStart) {
    y.segment(layout.omegaOffset(), bodies) = target.rotationStart->segment(layout.omegaOffset(), bodies);
    y.segment(layout.angleOffset(), bodies) = target.rotationStart->segment(layout.angleOffset(), bodies);
  }
  y.segment(layout.omegaOffset(), bodies) += h * w.k1.segment(layout.omegaOffset(), bodies);
  y.segment(layout.angleOffset(), bodies) += h * y.segment(layout.omegaOffset(), bodies);
}

}  // namespace particles
