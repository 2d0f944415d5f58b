#include "core/block_ldlt.hpp"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <stdexcept>
#include <utility>

namespace particles {

namespace {

using Block = Eigen::Map<Eigen::Matrix2d>;
using ConstBlock = Eigen::Map<const Eigen::Matrix2d>;

}  // namespace

void BlockLdlt::analyze(const Eigen::SparseMatrix<double>& a) {
  if (a.rows() != a.cols() || a.rows() % 2 != 0)
    throw std::invalid_argument("BlockLdlt: A must be square, 2 × 2 blocks");
  nodes_ = int(a.rows() / 2);
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();

  // The particles' graph, and its approximate-minimum-degree order (Eigen's ordering returns,
  // per new position, the old index).
  std::vector<Eigen::Triplet<double>> edges;
  edges.reserve(size_t(a.nonZeros()));
  for (int c = 0; c < int(a.cols()); ++c) {
    for (int p = outer[c]; p < outer[c + 1]; ++p) edges.emplace_back(inner[p] / 2, c / 2, 1.0);
  }
  Eigen::SparseMatrix<double> graph(nodes_, nodes_);
  graph.setFromTriplets(edges.begin(), edges.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(graph, order);
  perm_.assign(order.indices().data(), order.indices().data() + nodes_);
  inverse_.assign(size_t(nodes_), 0);
  for (int k = 0; k < nodes_; ++k) inverse_[size_t(perm_[size_t(k)])] = k;

  // A's upper block triangle in the new order: (column, row) pairs with row ≤ column.
  std::vector<std::pair<int, int>> upper;
  upper.reserve(size_t(a.nonZeros()) / 2 + size_t(nodes_));
  for (int c = 0; c < int(a.cols()); ++c) {
    const int column = inverse_[size_t(c / 2)];
    for (int p = outer[c]; p < outer[c + 1]; ++p) {
      const int row = inverse_[size_t(inner[p] / 2)];
      if (row <= column) upper.emplace_back(column, row);
    }
  }
  for (int k = 0; k < nodes_; ++k) upper.emplace_back(k, k);  // every pivot, even an empty one
  std::sort(upper.begin(), upper.end());
  upper.erase(std::unique(upper.begin(), upper.end()), upper.end());
  upperStart_.assign(size_t(nodes_) + 1, 0);
  upperRow_.resize(upper.size());
  for (size_t b = 0; b < upper.size(); ++b) {
    ++upperStart_[size_t(upper[b].first) + 1];
    upperRow_[b] = upper[b].second;
  }
  for (int k = 0; k < nodes_; ++k) upperStart_[size_t(k) + 1] += upperStart_[size_t(k)];
  upperValue_.assign(4 * upper.size(), 0.0);
  slotTarget_.assign(size_t(a.nonZeros()), -1);
  for (int c = 0; c < int(a.cols()); ++c) {
    const int column = inverse_[size_t(c / 2)];
    for (int p = outer[c]; p < outer[c + 1]; ++p) {
      const int row = inverse_[size_t(inner[p] / 2)];
      if (row > column) continue;
      const int* begin = upperRow_.data() + upperStart_[size_t(column)];
      const int* end = upperRow_.data() + upperStart_[size_t(column) + 1];
      const int block = int(std::lower_bound(begin, end, row) - upperRow_.data());
      slotTarget_[size_t(p)] = 4 * block + inner[p] % 2 + 2 * (c % 2);
    }
  }

  // The elimination tree, L's block counts per column and each block row's pattern (Davis's
  // ldl_symbolic): row k's pattern is every node on the tree paths from A's upper entries in
  // column k up to k, kept in topological order (children before parents), the order the numeric
  // factorisation takes it in; the same for every factorisation of the pattern, so found once.
  parent_.assign(size_t(nodes_), -1);
  std::vector<int> mark(size_t(nodes_), -1), path(size_t(nodes_), 0), count(size_t(nodes_), 0);
  rowPatternStart_.assign(size_t(nodes_) + 1, 0);
  rowPattern_.clear();
  for (int k = 0; k < nodes_; ++k) {
    mark[size_t(k)] = k;
    int top = nodes_;
    for (int p = upperStart_[size_t(k)]; p < upperStart_[size_t(k) + 1]; ++p) {
      int length = 0;
      for (int i = upperRow_[size_t(p)]; mark[size_t(i)] != k; i = parent_[size_t(i)]) {
        if (parent_[size_t(i)] == -1) parent_[size_t(i)] = k;
        ++count[size_t(i)];
        path[size_t(length++)] = i;
        mark[size_t(i)] = k;
      }
      while (length > 0) path[size_t(--top)] = path[size_t(--length)];
    }
    rowPattern_.insert(rowPattern_.end(), path.begin() + top, path.end());
    rowPatternStart_[size_t(k) + 1] = int(rowPattern_.size());
  }
  columnStart_.assign(size_t(nodes_) + 1, 0);
  factorMultiplyAdds_ = 10.0 * double(nodes_);  // the pivots' inverses
  for (int j = 0; j < nodes_; ++j) {
    columnStart_[size_t(j) + 1] = columnStart_[size_t(j)] + count[size_t(j)];
    // Column j's c blocks: each meets the ones above it once (c (c − 1) / 2 block products), and
    // each gives L(k, j) and its term of D(k) (two more).
    const double c = double(count[size_t(j)]);
    factorMultiplyAdds_ += 8.0 * (c * (c - 1.0) / 2.0 + 2.0 * c);
  }
  rowIndex_.assign(size_t(columnStart_.back()), 0);
  value_.assign(4 * rowIndex_.size(), 0.0);
  inverseD_.assign(size_t(nodes_), Eigen::Matrix2d::Zero());
  y_.assign(size_t(nodes_), Eigen::Matrix2d::Zero());
  filled_.assign(size_t(nodes_), 0);
  work_.resize(2 * nodes_);
}

bool BlockLdlt::factorize(const Eigen::SparseMatrix<double>& a) {
  if (a.nonZeros() != Eigen::Index(slotTarget_.size()) || a.rows() != rows()) {
    throw std::logic_error("BlockLdlt::factorize: A's pattern is not the analysed one");
  }
  std::fill(upperValue_.begin(), upperValue_.end(), 0.0);
  const double* aValue = a.valuePtr();
  for (size_t p = 0; p < slotTarget_.size(); ++p) {
    if (slotTarget_[p] >= 0) upperValue_[size_t(slotTarget_[p])] = aValue[p];
  }
  std::fill(filled_.begin(), filled_.end(), 0);
  for (int k = 0; k < nodes_; ++k) {
    // Y = A's upper block column k; then along row k's pattern (analyze).
    for (int p = upperStart_[size_t(k)]; p < upperStart_[size_t(k) + 1]; ++p) {
      y_[size_t(upperRow_[size_t(p)])] += ConstBlock(upperValue_.data() + 4 * p);
    }
    Eigen::Matrix2d d = y_[size_t(k)];
    y_[size_t(k)].setZero();
    for (int at = rowPatternStart_[size_t(k)]; at < rowPatternStart_[size_t(k) + 1]; ++at) {
      const int i = rowPattern_[size_t(at)];
      const Eigen::Matrix2d yi = y_[size_t(i)];
      y_[size_t(i)].setZero();
      const int end = columnStart_[size_t(i)] + filled_[size_t(i)];
      for (int p = columnStart_[size_t(i)]; p < end; ++p) {
        y_[size_t(rowIndex_[size_t(p)])].noalias() -= ConstBlock(value_.data() + 4 * p) * yi;
      }
      const Eigen::Matrix2d lki = yi.transpose() * inverseD_[size_t(i)];
      d.noalias() -= lki * yi;
      rowIndex_[size_t(end)] = k;
      Block(value_.data() + 4 * end) = lki;
      ++filled_[size_t(i)];
    }
    // D(k) is symmetric but for rounding; its inverse from the mean of the off-diagonal pair.
    const double offDiagonal = 0.5 * (d(0, 1) + d(1, 0));
    const double det = d(0, 0) * d(1, 1) - offDiagonal * offDiagonal;
    if (!(d(0, 0) > 0.0 && det > 0.0)) return false;  // also a NaN
    inverseD_[size_t(k)] << d(1, 1) / det, -offDiagonal / det, -offDiagonal / det, d(0, 0) / det;
  }
  return true;
}

// Both triangular solves by 2-vectors (one SSE2 register): L's block columns are stored
// column-major, so block · z is two columns times z's two numbers, and a row of Lᵀ · w is two
// products of a column with w, summed across at the end of the block column.
void BlockLdlt::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  using Vector = Eigen::Vector2d;
  using ConstVectorMap = Eigen::Map<const Vector>;
  using VectorMap = Eigen::Map<Vector>;
  const int n = nodes_;
  double* w = work_.data();
  const double* l = value_.data();
  const int* row = rowIndex_.data();
  for (int k = 0; k < n; ++k) work_.segment<2>(2 * k) = b.segment<2>(2 * perm_[size_t(k)]);
  for (int j = 0; j < n; ++j) {  // L z = P b, by block columns
    const double z0 = w[2 * j], z1 = w[2 * j + 1];
    for (int p = columnStart_[size_t(j)]; p < columnStart_[size_t(j) + 1]; ++p) {
      const double* block = l + 4 * p;
      VectorMap(w + 2 * row[p]) -= ConstVectorMap(block) * z0 + ConstVectorMap(block + 2) * z1;
    }
  }
  for (int j = 0; j < n; ++j) work_.segment<2>(2 * j) = inverseD_[size_t(j)] * work_.segment<2>(2 * j).eval();
  for (int j = n - 1; j >= 0; --j) {  // Lᵀ w = D⁻¹ z: row j of Lᵀ is column j of L
    Vector first = Vector::Zero(), second = Vector::Zero();
    for (int p = columnStart_[size_t(j)]; p < columnStart_[size_t(j) + 1]; ++p) {
      const double* block = l + 4 * p;
      const ConstVectorMap source(w + 2 * row[p]);
      first += ConstVectorMap(block).cwiseProduct(source);
      second += ConstVectorMap(block + 2).cwiseProduct(source);
    }
    w[2 * j] -= first.sum();
    w[2 * j + 1] -= second.sum();
  }
  x.resize(2 * n);
  for (int k = 0; k < n; ++k) x.segment<2>(2 * perm_[size_t(k)]) = work_.segment<2>(2 * k);
}

}  // namespace particles
