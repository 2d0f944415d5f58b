#include "core/implicit_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/force_jacobians.hpp"
#include "core/group_by_bucket.hpp"
#include "core/parallel_sparse.hpp"
#include "core/preconditioners/jacobi_preconditioner.hpp"
#include "core/projected_pcg.hpp"
#include "core/system.hpp"

namespace particles {

// The implicit step's matrix pattern: the Jacobians' (row, column) keys and the pinned
// coordinates it was built from, and which triplets' values go where in the compressed matrix,
// read so that threads fill whole values and rows, each summing in the triplets' order (the order
// a serial scatter adds in).
struct AssemblyPattern {
  bool valid = false;
  std::vector<int> dfdvKeys, dfdxKeys, pairKeys;
  std::vector<char> pinned;
  // Per value slot, the entries that land there (k < |D|: D's k-th, else K's (k − |D|)-th) from
  // slotStart[slot], and the coordinate whose diagonal it is (−1: none); per row of K, its
  // entries' indices from kRowStart[row]. pinnedColumnEntries: the entries (same numbering) in a
  // free row and an eliminated column, whose A value times the known Δv leaves the right-hand side.
  std::vector<int> slotStart, slotEntries, slotDiagonal, kRowStart, kRowEntries, pinnedColumnEntries;
  // The Jacobian pairs (ForceJacobians::pairs) by 2 × 2 blocks of A (BlockRef). Each block of A
  // they reach has its four slots (xx, yx, xy, yy; −1: a pinned coordinate's) and its references
  // pairBlockRefs[begin … end), in the pairs' order. Per point, its pairs' ends 2q (as a) or
  // 2q + 1 (as b) from pairPointStart[point], for K's products in b; pinnedPairEntries: the block
  // entries (r, c) in a free row and an eliminated column.
  struct PairBlock {
    int slot[4];
    int begin, end;
  };
  struct PinnedPairEntry {
    BlockRef ref;
    int r, c;
  };
  std::vector<PairBlock> pairBlocks;
  std::vector<BlockRef> pairBlockRefs;
  std::vector<int> pairPointStart, pairPointRefs;
  std::vector<PinnedPairEntry> pinnedPairEntries;
};

// What the stages fill, and what the step keeps from one step to the next.
struct ImplicitStep::Scratch {
  ForceJacobians jacobians;
  std::vector<ConstraintRow> constraintRows;
  ConstraintRowsJ rows;
  AssemblyPattern pattern;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<char> pinned, found, railed;
  std::vector<int> allRows, generalRows, railRows;  // constraint rows by how the solve takes them
  Eigen::SparseMatrix<double> matrix;
  Eigen::VectorXd k1, rhs, dv, known;  // k1: dy/dt at the start; known: eliminated coordinates' Δv
  std::vector<double> pairA, pairKu;  // per Jacobian pair: −η d − η² k (xx, xy, yy), k (x̄ − x_b + η (v_a − v_b))
  JacobiPreconditioner jacobi;
  LdltPreconditioner ldlt;
  bool ldltValid = false;               // factors (of an earlier or this step's A) of the current pattern
  bool autoDirect = false;              // auto has moved to the direct solve
  std::vector<int> cgIterationsWindow;  // auto: the last kAutoWindow CG steps' iterations
  double reuseDebt = 0.0;               // multiply-adds the stale factors' extra iterations have cost
  long factorizations = 0;
  ProjectedPcgScratch pcg;
  ImplicitStepStats stats;
};

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

// One implicit step's stages, in the order ImplicitStep::step runs them, over the scratch they fill.
class StepStages {
 public:
  StepStages(const Model& model, WorkerPool* pool, ImplicitStep::Scratch& w)
      : model_(model), pool_(pool), w_(w), n_(2 * Eigen::Index(model.layout.numPoints())) {}

  // Sorts the constraint rows: dropped (nothing free), eliminable (an axis-aligned rail on a
  // coordinate not yet railed), general (the rest). Marks fixed points' coordinates pinned.
  // Returns how many coordinates the rails would eliminate.
  int classifyRows();
  // The direct path's reduced coordinates: each rail's coordinate pinned, its Δv known.
  void eliminateRails(const Eigen::VectorXd& y);
  // A's pattern: rebuilt when the Jacobians' (row, column) sequence or the pinned set changed.
  bool patternChanged();
  void buildPattern() {
    buildMatrixPattern();
    mapTripletSlots();
    mapPairBlocks();
    mapPairEnds();
    w_.pattern.valid = true;
    w_.ldltValid = false;
  }
  // A = M − η D − η² K's values and b (see the header), in the pattern.
  void fillMatrix(double eta);
  void fillRightHandSide(const Eigen::VectorXd& y, double eta, const ImplicitTarget& target);
  // Δv into w.dv, by either solve; direct falls back to CG if A cannot be factored.
  void solveByCg(const Eigen::Ref<const Eigen::VectorXd>& v0, double tolerance);
  void solveDirect(const Eigen::Ref<const Eigen::VectorXd>& v0, double cgTolerance);

 private:
  bool pinned(Eigen::Index i) const { return w_.pinned[size_t(i)] != 0; }
  bool fixedDof(Eigen::Index i) const { return model_.invMass[i / 2] == 0.0; }
  // buildPattern's parts, in its order. A's pattern from the diagonal, the pairs' blocks and the
  // triplets (less what pinned coordinates leave out), and the keys it is checked against.
  void buildMatrixPattern();
  // Each triplet's value slot, and the reverse maps: per slot, per row of K.
  void mapTripletSlots();
  // The pairs' blocks of A, each with its slots and its references.
  void mapPairBlocks();
  // Per point, the pair ends it is.
  void mapPairEnds();
  // A block's row and column points.
  std::pair<int, int> blockPoints(BlockRef ref) const {
    const JacobianPair& pair = w_.jacobians.pairs[size_t(ref.pair)];
    return {ref.rowPoint(pair), ref.colPoint(pair)};
  }
  // Where entry (row, col) sits in A's value array (columns are sorted: compressed storage).
  int slotOf(Eigen::Index row, Eigen::Index col) const {
    const int* inner = w_.matrix.innerIndexPtr();
    const int* begin = inner + w_.matrix.outerIndexPtr()[col];
    const int* end = inner + w_.matrix.outerIndexPtr()[col + 1];
    return int(std::lower_bound(begin, end, int(row)) - inner);
  }
  // A block's four slots (xx, yx, xy, yy; −1: pinned out).
  void slotsOfBlock(BlockRef ref, int* slot) const {
    const auto [rowPoint, colPoint] = blockPoints(ref);
    for (int c = 0; c < 2; ++c) {
      for (int r = 0; r < 2; ++r) {
        const int row = 2 * rowPoint + r, col = 2 * colPoint + c;
        slot[r + 2 * c] = pinned(row) || pinned(col) ? -1 : slotOf(row, col);
      }
    }
  }
  // A's value from Jacobian entry `entry` (k < |D|: D's k-th, else K's (k − |D|)-th).
  double entryValue(int entry, double eta) const {
    const ForceJacobians& jac = w_.jacobians;
    const int dCount = int(jac.dfdv.size());
    return entry < dCount ? -eta * jac.dfdv[size_t(entry)].value()
                          : (-eta * eta) * jac.dfdx[size_t(entry - dCount)].value();
  }

  const Model& model_;
  WorkerPool* pool_;
  ImplicitStep::Scratch& w_;
  const Eigen::Index n_;
};

int StepStages::classifyRows() {
  w_.pinned.assign(size_t(n_), 0);
  for (Eigen::Index i = 0; i < n_; ++i) w_.pinned[size_t(i)] = fixedDof(i) ? 1 : 0;
  w_.known.setZero(n_);
  w_.allRows.clear();
  w_.generalRows.clear();
  w_.railRows.clear();
  w_.railed.assign(size_t(n_), 0);
  int eliminated = 0;
  for (size_t r = 0; r < w_.constraintRows.size(); ++r) {
    w_.allRows.push_back(int(r));
    const ConstraintRow& row = w_.constraintRows[r];
    bool touchesFree = false;
    for (int k = 0; k < row.count; ++k) touchesFree = touchesFree || model_.invMass[row.particle[size_t(k)]] != 0.0;
    if (!touchesFree) continue;  // nothing can meet it: dropped
    const int coordinate = axisAlignedCoordinate(row);
    if (coordinate >= 0 && !w_.railed[size_t(coordinate)]) {
      w_.railed[size_t(coordinate)] = 1;
      w_.railRows.push_back(int(r));
      ++eliminated;
    } else {
      w_.generalRows.push_back(int(r));
    }
  }
  return eliminated;
}

void StepStages::eliminateRails(const Eigen::VectorXd& y) {
  const Eigen::Index vOff = model_.layout.velocityOffset();
  for (int r : w_.railRows) {
    const int coordinate = axisAlignedCoordinate(w_.constraintRows[size_t(r)]);
    // J_i Δv_i = c = −J_i v₀ᵢ: the rail's coordinate ends the step at rest (Ċ = 0).
    w_.known[coordinate] = -y[vOff + coordinate];
    w_.pinned[size_t(coordinate)] = 1;
  }
}

bool StepStages::patternChanged() {
  const ForceJacobians& jac = w_.jacobians;
  const AssemblyPattern& pattern = w_.pattern;
  auto samePattern = [&](const ForceJacobians::Triplets& from, const std::vector<int>& keys) {
    if (2 * from.size() != keys.size()) return false;
    return !anyOf(pool_, from.size(), kRowChunk, w_.found,
                  [&](size_t k) { return ((from[k].row() ^ keys[2 * k]) | (from[k].col() ^ keys[2 * k + 1])) != 0; });
  };
  auto samePairs = [&] {
    const ForceJacobians::Pairs& pairs = jac.pairs;
    if (2 * pairs.size() != pattern.pairKeys.size()) return false;
    return !anyOf(pool_, pairs.size(), kRowChunk, w_.found, [&](size_t q) {
      return ((pairs[q].a ^ pattern.pairKeys[2 * q]) | (pairs[q].b ^ pattern.pairKeys[2 * q + 1])) != 0;
    });
  };
  return !pattern.valid || w_.matrix.rows() != n_ || pattern.pinned != w_.pinned ||
         !samePattern(jac.dfdv, pattern.dfdvKeys) || !samePattern(jac.dfdx, pattern.dfdxKeys) || !samePairs();
}

void StepStages::buildMatrixPattern() {
  const ForceJacobians& jac = w_.jacobians;
  const ForceJacobians::Pairs& pairs = jac.pairs;
  AssemblyPattern& pattern = w_.pattern;
  w_.triplets.clear();
  w_.triplets.reserve(size_t(n_) + jac.dfdv.size() + jac.dfdx.size() + 16 * pairs.size());
  for (Eigen::Index i = 0; i < n_; ++i) w_.triplets.emplace_back(i, i, 1.0);
  pattern.pairKeys.clear();
  for (int q = 0; q < int(pairs.size()); ++q) {
    pattern.pairKeys.push_back(pairs[size_t(q)].a);
    pattern.pairKeys.push_back(pairs[size_t(q)].b);
    for (BlockRef::Role role : BlockRef::kRoles) {
      const auto [rowPoint, colPoint] = blockPoints({q, role});
      for (int c = 0; c < 2; ++c) {
        for (int r = 0; r < 2; ++r) {
          const int row = 2 * rowPoint + r, col = 2 * colPoint + c;
          if (!pinned(row) && !pinned(col)) w_.triplets.emplace_back(row, col, 1.0);
        }
      }
    }
  }
  auto keysOf = [&](const ForceJacobians::Triplets& from, std::vector<int>& keys) {
    keys.clear();
    for (const auto& e : from) {
      keys.push_back(e.row());
      keys.push_back(e.col());
      if (!pinned(e.row()) && !pinned(e.col())) w_.triplets.emplace_back(e.row(), e.col(), 1.0);
    }
  };
  keysOf(jac.dfdv, pattern.dfdvKeys);
  keysOf(jac.dfdx, pattern.dfdxKeys);
  pattern.pinned = w_.pinned;
  w_.matrix.resize(n_, n_);
  w_.matrix.setFromTriplets(w_.triplets.begin(), w_.triplets.end());
  w_.matrix.makeCompressed();
}

void StepStages::mapTripletSlots() {
  const ForceJacobians& jac = w_.jacobians;
  AssemblyPattern& pattern = w_.pattern;
  // Each triplet's slot (−1: a pinned coordinate's, left out), and those in a free row and an
  // eliminated column.
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
  const size_t slots = size_t(w_.matrix.nonZeros());
  pattern.slotDiagonal.assign(slots, -1);
  for (Eigen::Index i = 0; i < n_; ++i) pattern.slotDiagonal[size_t(slotOf(i, i))] = int(i);
  groupByBucket(slots, slotOfEntry, pattern.slotStart, pattern.slotEntries);
  std::vector<int> rowOfEntry;
  rowOfEntry.reserve(jac.dfdx.size());
  for (const auto& e : jac.dfdx) rowOfEntry.push_back(int(e.row()));
  groupByBucket(size_t(n_), rowOfEntry, pattern.kRowStart, pattern.kRowEntries);
}

void StepStages::mapPairBlocks() {
  const ForceJacobians::Pairs& pairs = w_.jacobians.pairs;
  AssemblyPattern& pattern = w_.pattern;
  // Every pair's four blocks in the pairs' order, each found by its first slot that is not pinned
  // out, then grouped by that slot: the references of one block of A, in the pairs' order.
  std::vector<BlockRef> refs;
  refs.reserve(4 * pairs.size());
  std::vector<int> leadSlotOfRef(4 * pairs.size(), -1), blockStart, grouped;
  pattern.pinnedPairEntries.clear();
  for (int q = 0; q < int(pairs.size()); ++q) {
    for (BlockRef::Role role : BlockRef::kRoles) {
      const BlockRef ref{q, role};
      int slot[4];
      slotsOfBlock(ref, slot);
      for (int s : slot) {
        if (s >= 0) {
          leadSlotOfRef[refs.size()] = s;
          break;
        }
      }
      refs.push_back(ref);
      const auto [rowPoint, colPoint] = blockPoints(ref);
      for (int c = 0; c < 2; ++c) {
        for (int r = 0; r < 2; ++r) {
          const int row = 2 * rowPoint + r, col = 2 * colPoint + c;
          if (!pinned(row) && pinned(col) && !fixedDof(col)) pattern.pinnedPairEntries.push_back({ref, r, c});
        }
      }
    }
  }
  const size_t slots = size_t(w_.matrix.nonZeros());
  groupByBucket(slots, leadSlotOfRef, blockStart, grouped);
  pattern.pairBlockRefs.clear();
  for (int k : grouped) pattern.pairBlockRefs.push_back(refs[size_t(k)]);
  pattern.pairBlocks.clear();
  for (size_t slot = 0; slot < slots; ++slot) {
    if (blockStart[slot + 1] == blockStart[slot]) continue;
    AssemblyPattern::PairBlock block{};
    slotsOfBlock(pattern.pairBlockRefs[size_t(blockStart[slot])], block.slot);
    block.begin = blockStart[slot];
    block.end = blockStart[slot + 1];
    pattern.pairBlocks.push_back(block);
  }
}

void StepStages::mapPairEnds() {
  const ForceJacobians::Pairs& pairs = w_.jacobians.pairs;
  std::vector<int> pointOfEnd(2 * pairs.size());
  for (size_t q = 0; q < pairs.size(); ++q) {
    pointOfEnd[2 * q] = pairs[q].a;
    pointOfEnd[2 * q + 1] = pairs[q].b;
  }
  groupByBucket(size_t(n_ / 2), pointOfEnd, w_.pattern.pairPointStart, w_.pattern.pairPointRefs);
}

void StepStages::fillMatrix(double eta) {
  const AssemblyPattern& pattern = w_.pattern;
  const ForceJacobians::Pairs& pairs = w_.jacobians.pairs;
  // Slot by slot: the diagonal's M (1 for a pinned coordinate), then −η D and −η² K in the
  // triplets' order.
  double* values = w_.matrix.valuePtr();
  forChunks(pool_, size_t(w_.matrix.nonZeros()), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t slot = begin; slot < end; ++slot) {
      const int diagonal = pattern.slotDiagonal[slot];
      double value = diagonal < 0 ? 0.0 : (pinned(diagonal) ? 1.0 : model_.mass[diagonal / 2]);
      for (int k = pattern.slotStart[slot]; k < pattern.slotStart[slot + 1]; ++k)
        value += entryValue(pattern.slotEntries[size_t(k)], eta);
      values[slot] = value;
    }
  });
  // Then the pairs' part, block by block: A's (a, a) and (b, b) blocks gain −η d − η² k, (a, b)
  // and (b, a) lose it.
  std::vector<double>& pairA = w_.pairA;
  pairA.resize(3 * pairs.size());
  forChunks(pool_, pairs.size(), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t q = begin; q < end; ++q) {
      for (int j = 0; j < 3; ++j) pairA[3 * q + size_t(j)] = -eta * pairs[q].d[j] - eta * eta * pairs[q].k[j];
    }
  });
  forChunks(pool_, pattern.pairBlocks.size(), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      const AssemblyPattern::PairBlock& block = pattern.pairBlocks[b];
      double sum[3] = {0.0, 0.0, 0.0};
      for (int k = block.begin; k < block.end; ++k) {
        const BlockRef ref = pattern.pairBlockRefs[size_t(k)];
        const double* m = &pairA[3 * size_t(ref.pair)];
        const double sign = ref.sign();
        for (int j = 0; j < 3; ++j) sum[j] += sign * m[j];
      }
      const double entry[4] = {sum[0], sum[1], sum[1], sum[2]};  // xx, yx, xy, yy
      for (int j = 0; j < 4; ++j) {
        if (block.slot[j] >= 0) values[block.slot[j]] += entry[j];
      }
    }
  });
}

void StepStages::fillRightHandSide(const Eigen::VectorXd& y, double eta, const ImplicitTarget& target) {
  // b = M (v̄ − v_b) + η (f_b + K (x̄ − x_b + η v_b)), row by row; K's products straight from its
  // triplets, in their order, and from its pairs.
  const AssemblyPattern& pattern = w_.pattern;
  const ForceJacobians& jac = w_.jacobians;
  const ForceJacobians::Pairs& pairs = jac.pairs;
  const Eigen::Index vOff = model_.layout.velocityOffset();
  const Eigen::VectorXd* xShift = target.xShift;
  const Eigen::VectorXd* vShift = target.vShift;
  // A pair's K times that vector is k (u_a − u_b) at a and its negative at b.
  std::vector<double>& pairKu = w_.pairKu;
  pairKu.resize(2 * pairs.size());
  forChunks(pool_, pairs.size(), kRowChunk, [&](size_t begin, size_t end) {
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
  w_.rhs.resize(n_);
  forChunks(pool_, size_t(n_), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const double mass = model_.mass[Eigen::Index(i / 2)];
      double value = mass * w_.k1[vOff + Eigen::Index(i)];
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
      w_.rhs[Eigen::Index(i)] = pinned(Eigen::Index(i)) ? 0.0 : b;
    }
  });
  // The eliminated coordinates' known Δv times their columns of A leaves the free rows' side.
  const int dCount = int(jac.dfdv.size());
  for (int entry : pattern.pinnedColumnEntries) {
    const auto& e = entry < dCount ? jac.dfdv[size_t(entry)] : jac.dfdx[size_t(entry - dCount)];
    w_.rhs[e.row()] -= entryValue(entry, eta) * w_.known[e.col()];
  }
  for (const auto& [ref, r, c] : pattern.pinnedPairEntries) {
    const auto [rowPoint, colPoint] = blockPoints(ref);
    const double* m = &w_.pairA[3 * size_t(ref.pair)];
    const double entry = ref.sign() * m[r + c];  // xx, xy = yx, yy
    w_.rhs[2 * rowPoint + r] -= entry * w_.known[2 * colPoint + c];
  }
}

void StepStages::solveByCg(const Eigen::Ref<const Eigen::VectorXd>& v0, double tolerance) {
  ImplicitStepStats& stats = w_.stats;
  gatherRows(w_.constraintRows, w_.allRows, v0, nullptr, nullptr, w_.rows);
  w_.jacobi.setMatrix(pool_, w_.matrix, w_.pinned);
  w_.jacobi.prepareRows(w_.rows);
  const int maxIterations = int(std::max<Eigen::Index>(2 * n_, 10));
  stats.solver = ImplicitSolver::cg;
  stats.schurRows = 0;
  stats.iterations =
      solveProjectedPcg(pool_, w_.matrix, w_.rhs, w_.rows, w_.jacobi, w_.dv, tolerance, maxIterations, w_.pcg)
          .iterations;
}

void StepStages::solveDirect(const Eigen::Ref<const Eigen::VectorXd>& v0, double cgTolerance) {
  ImplicitStepStats& stats = w_.stats;
  gatherRows(w_.constraintRows, w_.generalRows, v0, &w_.pinned, &w_.known, w_.rows);
  stats.solver = ImplicitSolver::direct;
  stats.schurRows = w_.rows.size();
  auto refactor = [&] {
    if (!w_.ldltValid) w_.ldlt.analyze(w_.matrix);
    w_.ldltValid = w_.ldlt.factorize(w_.matrix);
    w_.reuseDebt = 0.0;
    stats.factorized = true;
    ++w_.factorizations;
    return w_.ldltValid;
  };
  // Refactor when the stale factors' extra iterations have cost as much as a factorisation
  // (the rent-or-buy rule: never more than twice the cheaper of the two choices in hindsight).
  bool ok = w_.ldltValid && w_.reuseDebt < w_.ldlt.factorCost() ? true : refactor();
  if (ok) {
    w_.ldlt.prepareRows(w_.rows);
    // A's own factors give the answer in one solve; an earlier step's iterate from there.
    ProjectedPcgResult r =
        solveProjectedPcg(pool_, w_.matrix, w_.rhs, w_.rows, w_.ldlt, w_.dv, kDirectTolerance, kMaxReuseIterations,
                          w_.pcg, stats.factorized ? PcgStart::exact : PcgStart::preconditioned);
    stats.iterations = r.iterations;
    if (!r.converged && !stats.factorized) {
      // Factors too far from A to converge soon: A's own, and on from here.
      ok = refactor();
      if (ok) {
        w_.ldlt.prepareRows(w_.rows);
        r = solveProjectedPcg(pool_, w_.matrix, w_.rhs, w_.rows, w_.ldlt, w_.dv, kDirectTolerance, kMaxReuseIterations,
                              w_.pcg, PcgStart::exact);
        stats.iterations += r.iterations;
      }
    }
    // What reuse cost beyond A's own factors' one solve: the residual's check and the iterations.
    if (ok && !stats.factorized) w_.reuseDebt += double(r.iterations + 1) * w_.ldlt.iterationCost();
  }
  if (!ok) {
    // Not positive definite (cannot happen with the forces' negative semi-definite blocks; a
    // guard): this step by CG, which needs no factors.
    w_.ldltValid = false;
    solveByCg(v0, cgTolerance);
  } else {
    w_.dv += w_.known;
  }
}

}  // namespace

double autoDirectIterations(long freeCoordinates) {
  return 14.0 * std::pow(double(std::max(freeCoordinates, 1L)) / 1250.0, 0.3);
}

ImplicitStep::ImplicitStep() : w_(std::make_unique<Scratch>()) {}
ImplicitStep::~ImplicitStep() = default;
ImplicitStep::ImplicitStep(ImplicitStep&&) noexcept = default;
ImplicitStep& ImplicitStep::operator=(ImplicitStep&&) noexcept = default;

const ImplicitStepStats& ImplicitStep::stats() const {
  return w_->stats;
}
long ImplicitStep::factorizations() const {
  return w_->factorizations;
}

ImplicitStep::LinearSystem ImplicitStep::lastSystem() const {
  return {w_->matrix, w_->rhs, w_->dv, w_->constraintRows};
}

void ImplicitStep::step(System& system, Eigen::VectorXd& y, double t, double h, const ImplicitTarget& target,
                        double cgTolerance) {
  Scratch& w = *w_;
  const Model& model = system.model();
  const StateLayout& layout = model.layout;
  const Eigen::Index n = 2 * Eigen::Index(layout.numPoints());
  const Eigen::Index vOff = layout.velocityOffset();
  const double eta = target.eta;
  WorkerPool* pool = system.pool();
  StepStages stages(model, pool, w);

  system.derivEval(y, t, w.k1, System::ConstraintForces::skip);  // [v₀ | f₀/m | ω₀ | τ₀/I]
  system.forceJacobians(y, t, w.jacobians);
  w.constraintRows.clear();
  const StateView s0(layout, y);
  for (const auto& c : system.constraints()) w.constraintRows.push_back(c->evaluate(s0));

  // Which solve: the direct one eliminates axis-aligned rails and takes the other rows through
  // its Schur complement, so it needs those to be few.
  const int eliminated = stages.classifyRows();
  const int generalRows = int(w.generalRows.size());
  const long freeCoordinates = long(std::count(w.pinned.begin(), w.pinned.end(), 0)) - eliminated;
  const ImplicitSolver requested = system.implicitSolver();
  const bool automatic = requested == ImplicitSolver::automatic;
  ImplicitSolver solver = requested;
  if (automatic) {
    solver = w.autoDirect && generalRows <= kMaxSchurRows ? ImplicitSolver::direct : ImplicitSolver::cg;
  }
  if (solver == ImplicitSolver::direct && generalRows > kMaxSchurRows) {
    throw ImplicitSolverError(fmt::format(
        "implicit_solver: direct: {} constraint rows are neither fixed points nor axis-aligned rails, and the direct "
        "solve takes at most {} such rows (their Schur complement is dense); use implicit_solver: cg or auto",
        generalRows, kMaxSchurRows));
  }
  const bool direct = solver == ImplicitSolver::direct && n > 0;
  if (direct) stages.eliminateRails(y);

  // A = M − η D − η² K over the free coordinates; a pinned one's row and column are the identity.
  // The Jacobians' pattern only changes when a contact or a mouse spring starts or ends, so A's
  // pattern is built once and its values are filled into it while the Jacobians' (row, column)
  // sequence is the one it was built from (a full setFromTriplets sorts and merges every triplet
  // again).
  if (stages.patternChanged()) stages.buildPattern();
  stages.fillMatrix(eta);
  stages.fillRightHandSide(y, eta, target);

  // Δv with J Δv = −J v₀, so that v₁ keeps every constraint's Ċ = 0 (J at x₀).
  const Eigen::Ref<const Eigen::VectorXd> v0 = y.segment(vOff, n);
  if (w.dv.size() != n) w.dv.setZero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (w.pinned[size_t(i)]) w.dv[i] = 0.0;  // the last step's Δv is the first guess
  }
  ImplicitStepStats& stats = w.stats;
  stats = {};
  stats.eliminated = direct ? eliminated : 0;
  if (direct) {
    stages.solveDirect(v0, cgTolerance);
  } else {
    stages.solveByCg(v0, cgTolerance);
    // auto: CG steps dearer than the direct solve at this size, on average, move the run to it.
    if (automatic && generalRows <= kMaxSchurRows) {
      std::vector<int>& window = w.cgIterationsWindow;
      if (int(window.size()) == kAutoWindow) window.erase(window.begin());
      window.push_back(stats.iterations);
      const double mean = double(std::accumulate(window.begin(), window.end(), 0)) / double(window.size());
      if (int(window.size()) == kAutoWindow && mean > autoDirectIterations(freeCoordinates)) w.autoDirect = true;
    }
  }

  const Eigen::VectorXd* xShift = target.xShift;
  forSegments(pool, n, [&](long i, long len) {
    y.segment(vOff + i, len) += w.dv.segment(i, len);
    if (xShift) y.segment(i, len) += xShift->segment(i, len);
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
