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
// over all of them (its share of a backward Euler step: bench/README.md, "Spring Jacobians by pairs").
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

// A force along a − b that depends only on x_a − x_b and v_a − v_b (a spring), with f_b = −f_a
// and ∂f_a/∂x_a = k, ∂f_a/∂v_a = d: its K is [k −k; −k k] and its D [d −d; −d d] on points
// (a, b). k and d are symmetric, so a pair is two points and six numbers (xx, xy, yy of each),
// not 32 triplets: the implicit step assembles and checks its pattern per pair.
struct JacobianPair {
  int a, b;
  double k[3], d[3];
  JacobianPair() = default;
  JacobianPair(int aPoint, int bPoint, const Eigen::Matrix2d& kBlock, const Eigen::Matrix2d& dBlock)
      : a(aPoint),
        b(bPoint),
        k{kBlock(0, 0), kBlock(0, 1), kBlock(1, 1)},
        d{dBlock(0, 0), dBlock(0, 1), dBlock(1, 1)} {}
};

// One of the four 2 × 2 blocks that a pair reaches in K (and D, and the implicit step's
// A = M − η D − η² K): its (a, a) and (b, b) blocks add the pair's block, (a, b) and (b, a)
// subtract it, as ForceJacobians::expanded writes them out.
struct BlockRef {
  enum class Role : unsigned char { aa, bb, ab, ba };
  static constexpr Role kRoles[4] = {Role::aa, Role::bb, Role::ab, Role::ba};

  int pair;  // index into ForceJacobians::pairs
  Role role;

  int rowPoint(const JacobianPair& p) const { return role == Role::aa || role == Role::ab ? p.a : p.b; }
  int colPoint(const JacobianPair& p) const { return role == Role::aa || role == Role::ba ? p.a : p.b; }
  double sign() const { return role == Role::aa || role == Role::bb ? 1.0 : -1.0; }
};

struct ForceJacobians {
  using Triplets = std::vector<JacobianEntry, DefaultInitAllocator<JacobianEntry>>;
  using Pairs = std::vector<JacobianPair, DefaultInitAllocator<JacobianPair>>;
  Triplets dfdx;  // K, N/m
  Triplets dfdv;  // D, N·s/m
  Pairs pairs;    // more of K and D, by pairs of points
  // The System's threads, which a force may fill its own fixed range of entries on (null: serial).
  WorkerPool* pool = nullptr;

  void clear() {
    dfdx.clear();
    dfdv.clear();
    pairs.clear();
  }
  // ∂f_row/∂(x or v)_col += b, for points row and col. All four entries, zeros too: the pattern
  // then depends on which forces act, not on their values (an axis-aligned spring's off-diagonal
  // zeros would otherwise come and go), so backward Euler can keep its matrix's pattern.
  static void addBlock(Triplets& to, int rowPoint, int colPoint, const Eigen::Matrix2d& b) {
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) to.emplace_back(2 * rowPoint + r, 2 * colPoint + c, b(r, c));
    }
  }
  // The same K and D with every pair written out as triplets (16 each): for a reader that wants
  // one form (the tests' dense matrices).
  ForceJacobians expanded() const {
    ForceJacobians out;
    out.dfdx = dfdx;
    out.dfdv = dfdv;
    for (const JacobianPair& p : pairs) {
      const Eigen::Matrix2d k{{p.k[0], p.k[1]}, {p.k[1], p.k[2]}}, d{{p.d[0], p.d[1]}, {p.d[1], p.d[2]}};
      for (auto [to, block] : {std::pair{&out.dfdx, k}, std::pair{&out.dfdv, d}}) {
        addBlock(*to, p.a, p.a, block);
        addBlock(*to, p.b, p.b, block);
        addBlock(*to, p.a, p.b, -block);
        addBlock(*to, p.b, p.a, -block);
      }
    }
    return out;
  }
};

}  // namespace particles
