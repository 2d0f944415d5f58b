#pragma once
// Internal to the core: A = M − η D − η² K and b of the implicit step (core/implicit_step.hpp), and
// the scratch the step's stages fill. The Jacobians' pattern only changes when a contact or a mouse
// spring starts or ends, so A's pattern is built once and its values are filled into it while the
// Jacobians' (row, column) sequence is the one it was built from (a full setFromTriplets sorts and
// merges every triplet again). Threads fill whole values and rows, each summing in the triplets'
// order (the order a serial scatter adds in), so A and b are the same bits on any thread count.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <utility>
#include <vector>

#include "core/force_jacobians.hpp"
#include "core/implicit_step.hpp"
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

// The stages that build A's pattern and fill A and b, over the scratch of one ImplicitStep.
class ImplicitAssembly {
 public:
  ImplicitAssembly(const Model& model, WorkerPool* pool, ImplicitStep::Scratch& w)
      : model_(model), pool_(pool), w_(w), n_(2 * Eigen::Index(model.layout.numPoints())) {}

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
  // A = M − η D − η² K's values and b (see core/implicit_step.hpp), in the pattern.
  void fillMatrix(double eta);
  void fillRightHandSide(const Eigen::VectorXd& y, double eta, const ImplicitTarget& target);

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

}  // namespace particles
