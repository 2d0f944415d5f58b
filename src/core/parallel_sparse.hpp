#pragma once
// The threaded products of the core's conjugate-gradient loops (backward Euler's,
// integrators/backward_euler.cpp, and the constraint solver's, constraint_solver.cpp), each
// summing in an order that does not depend on the thread count (core/worker_pool.hpp): a
// column's entries in their stored order, a dot product's chunks in chunk order.

#include <Eigen/SparseCore>
#include <vector>

#include "core/worker_pool.hpp"

namespace particles {

// Rows (or columns, or value slots) per chunk of the threaded sparse loops.
constexpr size_t kRowChunk = 8192;

// out = A x for a symmetric A stored whole (compressed, column-major): out_i = Σ_k A(k, i) x_k,
// column i's entries summed in their stored order, alternately into two sums that are added at
// the end (each addition then waits on half as many: a column of the 25² cloth's A holds about
// ten), so that threads take whole columns.
void multiplySymmetric(WorkerPool* pool, const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& x,
                       Eigen::VectorXd& out);

// x·y in fixed chunks added in order. `partials` is scratch the caller keeps.
double dotChunks(WorkerPool* pool, const Eigen::VectorXd& x, const Eigen::VectorXd& y, std::vector<double>& partials);

}  // namespace particles
