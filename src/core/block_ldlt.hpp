#pragma once
// A sparse LDLᵀ factorisation over 2 × 2 blocks, A = Pᵀ L D Lᵀ P, for the implicit step's matrix
// (core/preconditioners/ldlt_preconditioner.hpp): L is block unit lower triangular, D block
// diagonal with symmetric positive definite 2 × 2 blocks, P a permutation of the particles.
//
// Why not a scalar factorisation (Eigen's SimplicialLDLT, which this replaced): a particle's x and
// y always share their row and column pattern, so a scalar factor spends an index, a branch and
// a scattered store on every multiply-add, four times over the same block; here each index
// carries a 2 × 2 product (8 multiply-adds). Same algorithm otherwise, the up-looking one of
// Davis's LDL (ACM TOMS 31(4), 2005; "Direct Methods for Sparse Linear Systems", ch. 4), block
// row k of L from a sparse triangular solve along the elimination tree:
//   Y(i) = D(i) L(k,i)ᵀ solves  Σ_{j ≤ i} L(i,j) Y(j) = A(i,k)  for the i < k in row k's pattern,
//   L(k,i) = Y(i)ᵀ D(i)⁻¹,   D(k) = A(k,k) − Σ_i Y(i)ᵀ D(i)⁻¹ Y(i).
// The ordering is approximate minimum degree (Eigen's AMD) on the particles' graph; the ordering,
// the elimination tree and L's column counts depend only on the pattern (analyze), the numbers
// are refactored (factorize) as often as the owner wants.
// The blocks against Eigen's SimplicialLDLT with the same ordering and fill, measured on the 25²
// and 100² cloths' A: bench/README.md, "Block LDLᵀ" (timings go stale in comments).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace particles {

class BlockLdlt {
 public:
  // A's pattern (n × n, n even, structurally symmetric, column-major compressed; coordinate 2p + d
  // is particle p's x (d = 0) or y (d = 1)). Rows and columns of the same particle share a block.
  void analyze(const Eigen::SparseMatrix<double>& a);
  // A's numbers, with the analysed pattern (its size is checked, not every index). False when a
  // pivot block is not positive definite (or not a number).
  bool factorize(const Eigen::SparseMatrix<double>& a);

  // x = A⁻¹ b (in place: x may be b).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

  Eigen::Index rows() const { return 2 * Eigen::Index(nodes_); }
  // L's strictly-lower 2 × 2 blocks, and the multiply-adds of one factorisation (8 per product of
  // two blocks: a block column of c blocks takes c (c − 1) / 2 + 2 c of them, plus the pivots'
  // inverses) and of one solve (4 per block each way, 4 per pivot).
  long blocks() const { return long(rowIndex_.size()); }
  double factorMultiplyAdds() const { return factorMultiplyAdds_; }
  double solveMultiplyAdds() const { return 8.0 * double(blocks()) + 4.0 * double(nodes_); }

 private:
  int nodes_ = 0;
  std::vector<int> perm_, inverse_;  // perm_[k]: the particle at position k; inverse_: its position
  // A's upper block triangle in the new order, column by column: the block rows (≤ k) and where
  // each of A's scalar slots goes (−1: the lower triangle, not read).
  std::vector<int> upperStart_, upperRow_, slotTarget_;
  std::vector<double> upperValue_;  // 4 per block, column-major
  // The elimination tree and L, by block columns: column j's blocks from columnStart_[j], rows in
  // increasing order, each 4 values (column-major); D⁻¹ per column.
  std::vector<int> parent_, columnStart_, rowIndex_;
  std::vector<double> value_;
  std::vector<Eigen::Matrix2d> inverseD_;
  double factorMultiplyAdds_ = 0.0;
  // Each block row's pattern in the order the factorisation takes it, from rowPatternStart_[k].
  std::vector<int> rowPatternStart_, rowPattern_;
  // The factorisation's work arrays: Y's blocks, how many blocks each column holds so far.
  std::vector<Eigen::Matrix2d> y_;
  std::vector<int> filled_;
  mutable Eigen::VectorXd work_;
};

}  // namespace particles
