#pragma once
// The force Jacobians an implicit integrator linearises with (docs/physics.md §3; Baraff & Witkin,
// "Large Steps in Cloth Simulation", SIGGRAPH 1998, §5): K = ∂f/∂x and D = ∂f/∂v over the points'
// translational coordinates (2 per point, the force accumulator's layout), kept as sparse
// triplets; entries at the same place add up.
//
// Every block a force adds is symmetric and negative semi-definite, so that M − h D − h² K stays
// symmetric positive definite and conjugate gradients apply (the spring drops the part of its K
// that would break this, damped_spring_force.hpp). A force that adds nothing is treated
// explicitly by backward Euler: exact for gravity, whose Jacobians are zero.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/worker_pool.hpp"

namespace particles {

// One entry of K or D: ∂f_row/∂(x or v)_col. Eigen::Triplet's shape (row(), col(), value(), so
// setFromTriplets takes it), with a trivial default constructor: the springs size their range of
// entries and then fill it on the threads, and a vector of Eigen::Triplet would first write zeros
// over all of them (5 % of a backward Euler step on the 25² cloth).
struct JacobianEntry {
  int rowIndex, colIndex;
  double entryValue;
  JacobianEntry() = default;
  JacobianEntry(int row, int col, double value) : rowIndex(row), colIndex(col), entryValue(value) {}
  int row() const { return rowIndex; }
  int col() const { return colIndex; }
  double value() const { return entryValue; }
};

// An allocator whose value-initialising construct (what vector::resize calls) default-initialises
// instead: for trivially constructible types, no writes at all.
template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  using std::allocator<T>::allocator;
  template <typename U>
  void construct(U* at) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(at)) U;
  }
  template <typename U, typename... Args>
  void construct(U* at, Args&&... args) {
    ::new (static_cast<void*>(at)) U(std::forward<Args>(args)...);
  }
};

struct ForceJacobians {
  using Triplets = std::vector<JacobianEntry, DefaultInitAllocator<JacobianEntry>>;
  Triplets dfdx;  // K, N/m
  Triplets dfdv;  // D, N·s/m
  // The System's threads, which a force may fill its own fixed range of entries on (null: serial).
  WorkerPool* pool = nullptr;

  void clear() {
    dfdx.clear();
    dfdv.clear();
  }
  // ∂f_row/∂(x or v)_col += b, for points row and col. All four entries, zeros too: the pattern
  // then depends on which forces act, not on their values (an axis-aligned spring's off-diagonal
  // zeros would otherwise come and go), so backward Euler can keep its matrix's pattern.
  static void addBlock(Triplets& to, int rowPoint, int colPoint, const Eigen::Matrix2d& b) {
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) to.emplace_back(2 * rowPoint + r, 2 * colPoint + c, b(r, c));
    }
  }
  // A force along a − b that depends only on x_a − x_b (or v_a − v_b), f_b = −f_a, with
  // ∂f_a/∂x_a = b: the blocks are [b −b; −b b].
  static void addPair(Triplets& to, int a, int bPoint, const Eigen::Matrix2d& b) {
    addBlock(to, a, a, b);
    addBlock(to, bPoint, bPoint, b);
    addBlock(to, a, bPoint, -b);
    addBlock(to, bPoint, a, -b);
  }
  // The 16 entries addPair adds, written at `at` (which must hold 16) in the same order.
  static constexpr int kPairEntries = 16;
  static void writePair(JacobianEntry* at, int a, int bPoint, const Eigen::Matrix2d& b) {
    const int rows[4] = {a, bPoint, a, bPoint}, cols[4] = {a, bPoint, bPoint, a};
    for (int block = 0; block < 4; ++block) {
      const double sign = block < 2 ? 1.0 : -1.0;
      for (int r = 0; r < 2; ++r) {
        for (int c = 0; c < 2; ++c) {
          *at++ = JacobianEntry(2 * rows[block] + r, 2 * cols[block] + c, sign * b(r, c));
        }
      }
    }
  }
};

}  // namespace particles
