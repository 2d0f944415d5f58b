// The sparse LDLᵀ over 2 × 2 blocks (core/block_ldlt.hpp), the implicit step's direct solve:
// against a dense factorisation, its fill on patterns whose fill is known, and its refusals.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/block_ldlt.hpp"

using namespace particles;

namespace {

// A "spring net" matrix over `particles` particles: a mass on the diagonal, and per edge (a, b) a
// symmetric positive semi-definite 2 × 2 block K added at (a, a) and (b, b) and subtracted at
// (a, b) and (b, a), as M − h² ∂f/∂x is for springs. `pinned` coordinates keep only their
// diagonal (1), as the implicit step's eliminated ones do, so a particle's block may be half
// pinned. Fixed seed: the same matrix every run.
Eigen::SparseMatrix<double> springNet(int particles, const std::vector<std::pair<int, int>>& edges,
                                      const std::vector<int>& pinned = {}, unsigned seed = 7) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const int n = 2 * particles;
  std::vector<char> isPinned(size_t(n), 0);
  for (int i : pinned) isPinned[size_t(i)] = 1;
  std::vector<Eigen::Triplet<double>> t;
  auto add = [&](int r, int c, double v) {
    if (!isPinned[size_t(r)] && !isPinned[size_t(c)]) t.emplace_back(r, c, v);
  };
  for (auto [a, b] : edges) {
    Eigen::Matrix2d g;
    g << uniform(random), uniform(random), uniform(random), uniform(random);
    const Eigen::Matrix2d k = 100.0 * (g * g.transpose() + 0.1 * Eigen::Matrix2d::Identity());
    for (int d = 0; d < 2; ++d) {
      for (int e = 0; e < 2; ++e) {
        add(2 * a + d, 2 * a + e, k(d, e));
        add(2 * b + d, 2 * b + e, k(d, e));
        add(2 * a + d, 2 * b + e, -k(d, e));
        add(2 * b + d, 2 * a + e, -k(d, e));
      }
    }
  }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, isPinned[size_t(i)] ? 1.0 : 0.002 * (1.0 + 0.5 * uniform(random)));
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

// A w × h grid's structural edges (the demo cloth's springs).
std::vector<std::pair<int, int>> gridEdges(int w, int h) {
  std::vector<std::pair<int, int>> edges;
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      if (c + 1 < w) edges.emplace_back(r * w + c, r * w + c + 1);
      if (r + 1 < h) edges.emplace_back(r * w + c, (r + 1) * w + c);
    }
  }
  return edges;
}

Eigen::VectorXd rightHandSide(Eigen::Index n) {
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b[i] = std::sin(0.7 * double(i)) + 0.1 * double(i % 5);
  return b;
}

double relativeError(const Eigen::VectorXd& x, const Eigen::VectorXd& exact) {
  return (x - exact).norm() / exact.norm();
}

}  // namespace

TEST_CASE("BlockLdlt: solves a spring net as a dense factorisation does, refactored with new numbers") {
  // A 12 × 9 grid with a few long-range edges, and a fixed particle and a railed coordinate.
  std::vector<std::pair<int, int>> edges = gridEdges(12, 9);
  edges.insert(edges.end(), {{0, 50}, {7, 100}, {33, 34 + 36}});
  const std::vector<int> pinned = {0, 1, 2 * 5 + 1};
  for (unsigned seed : {7u, 8u}) {
    CAPTURE(seed);
    const Eigen::SparseMatrix<double> a = springNet(108, edges, pinned, seed);
    BlockLdlt ldlt;
    ldlt.analyze(a);
    REQUIRE(ldlt.factorize(a));
    const Eigen::VectorXd b = rightHandSide(a.rows());
    const Eigen::VectorXd exact = Eigen::MatrixXd(a).ldlt().solve(b);
    Eigen::VectorXd x;
    ldlt.solve(b, x);
    CHECK(relativeError(x, exact) < 1e-9);
    // New numbers on the same pattern (the implicit step's every refactorisation).
    const Eigen::SparseMatrix<double> a2 = springNet(108, edges, pinned, seed + 100);
    REQUIRE(ldlt.factorize(a2));
    ldlt.solve(b, x);
    CHECK(relativeError(x, Eigen::MatrixXd(a2).ldlt().solve(b)) < 1e-9);
    // In place.
    Eigen::VectorXd inPlace = b;
    ldlt.solve(inPlace, inPlace);
    CHECK(inPlace == x);
  }
}

TEST_CASE("BlockLdlt: fill where it is known, none on a chain and all on a clique") {
  SUBCASE("a chain's blocks are its edges, in any order") {
    const std::vector<std::pair<int, int>> edges = {{0, 3}, {3, 1}, {1, 4}, {4, 2}, {2, 5}};
    const Eigen::SparseMatrix<double> a = springNet(6, edges);
    BlockLdlt ldlt;
    ldlt.analyze(a);
    CHECK(ldlt.blocks() == 5);
    REQUIRE(ldlt.factorize(a));
    // Each column holds at most one block: 8 · 2 products per block plus the pivots'.
    CHECK(ldlt.factorMultiplyAdds() == doctest::Approx(8.0 * 2.0 * 5 + 10.0 * 6));
    Eigen::VectorXd x;
    ldlt.solve(rightHandSide(12), x);
    CHECK(relativeError(x, Eigen::MatrixXd(a).ldlt().solve(rightHandSide(12))) < 1e-9);
  }
  SUBCASE("a clique of 7 fills the lower triangle") {
    std::vector<std::pair<int, int>> edges;
    for (int i = 0; i < 7; ++i) {
      for (int j = i + 1; j < 7; ++j) edges.emplace_back(i, j);
    }
    const Eigen::SparseMatrix<double> a = springNet(7, edges);
    BlockLdlt ldlt;
    ldlt.analyze(a);
    CHECK(ldlt.blocks() == 21);
    REQUIRE(ldlt.factorize(a));
    Eigen::VectorXd x;
    ldlt.solve(rightHandSide(14), x);
    CHECK(relativeError(x, Eigen::MatrixXd(a).ldlt().solve(rightHandSide(14))) < 1e-9);
  }
}

TEST_CASE("BlockLdlt: refuses what it cannot factor") {
  const std::vector<std::pair<int, int>> edges = gridEdges(4, 3);
  Eigen::SparseMatrix<double> a = springNet(12, edges);
  BlockLdlt ldlt;
  ldlt.analyze(a);
  REQUIRE(ldlt.factorize(a));
  SUBCASE("an indefinite matrix: a pivot block that is not positive definite") {
    a.coeffRef(5, 5) = -a.coeffRef(5, 5) - 1000.0;
    CHECK_FALSE(ldlt.factorize(a));
  }
  SUBCASE("a NaN") {
    a.coeffRef(0, 0) = std::nan("");
    CHECK_FALSE(ldlt.factorize(a));
  }
  SUBCASE("another pattern (its size: the caller keeps the pattern it analysed)") {
    const Eigen::SparseMatrix<double> other = springNet(12, gridEdges(6, 2));
    CHECK_THROWS_AS(ldlt.factorize(other), std::logic_error);
  }
  SUBCASE("an odd size") {
    Eigen::SparseMatrix<double> odd(3, 3);
    odd.setIdentity();
    CHECK_THROWS_AS(ldlt.analyze(odd), std::invalid_argument);
  }
}
