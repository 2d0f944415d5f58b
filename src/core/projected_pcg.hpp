#pragma once
// Projected preconditioned conjugate gradients (Gould, Hribar & Nocedal 2001; Baraff & Witkin
// 1998 §5.3's "filter" is its one-particle case): solves A x = b over the x with J x = c, for the
// implicit integrators (core/implicit_step.hpp). With a preconditioner G ≈ A the preconditioned
// residual is projected onto J's null space,
//   g = P r,   P = G⁻¹ − G⁻¹ Jᵀ S⁻¹ J G⁻¹,   S = J G⁻¹ Jᵀ (one row per constraint).
// At the solution r is not zero but Jᵀλ (λ: the constraint impulses), and it grows while g
// shrinks; computed plainly, P r then loses J g = 0 to rounding and the iterates drift off
// J x = c, step after step, to the unconstrained answer (seen: a 25-particle chain on a rail fell
// freely). Gould et al.'s residual update keeps r small instead: r ← r − Jᵀ S⁻¹ J G⁻¹ r (twice,
// the second refining the first), then g = G⁻¹ r. Without constraints this is plain PCG.
// Eigen's ConjugateGradient takes no such projection, hence this loop.
//
// The preconditioners (core/preconditioners/): Jacobi, G = diag(A) (CG's default); and a sparse
// LDLᵀ factorisation of A itself (the direct solve), with which the loop ends after one
// iteration when the factors are A's, and after a few when they are an earlier step's.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "core/worker_pool.hpp"

namespace particles {

// The rows of J x = c, each with up to four (column, value) pairs (two particles × x, y; column
// −1 unused): products with J and Jᵀ cost O(rows), not O(n).
struct ConstraintRowsJ {
  std::vector<std::array<int, 4>> columns;
  std::vector<std::array<double, 4>> values;
  Eigen::VectorXd c;

  int size() const { return int(columns.size()); }
  // out = J z.
  void multiply(const Eigen::VectorXd& z, Eigen::VectorXd& out) const;
  // z −= Jᵀ λ, each entry scaled by scale[column] when scale is given.
  void subtractTransposed(const Eigen::VectorXd& lambda, Eigen::VectorXd& z,
                          const Eigen::VectorXd* scale = nullptr) const;
};

// G ≈ A: what preconditions the loop and defines its projection.
class PcgPreconditioner {
 public:
  virtual ~PcgPreconditioner() = default;
  // Forms and factors S = J G⁻¹ Jᵀ for these rows, once per solve. A row that G leaves no freedom
  // (all its coordinates pinned) gets S = 1 and c = 0: no Δx can meet it, and it is dropped.
  virtual void prepareRows(ConstraintRowsJ& rows) = 0;
  // g = G⁻¹ r.
  virtual void apply(WorkerPool* pool, const Eigen::VectorXd& r, Eigen::VectorXd& g) = 0;
  // λ = S⁻¹ rhs.
  virtual void solveSchur(const Eigen::VectorXd& rhs, Eigen::VectorXd& lambda) = 0;
  // z −= G⁻¹ Jᵀ λ.
  virtual void subtractPreconditionedJt(const ConstraintRowsJ& rows, const Eigen::VectorXd& lambda,
                                        Eigen::VectorXd& z) = 0;
  // After the projection's r −= Jᵀ λ: brings g = G⁻¹ r up to date (by default g −= G⁻¹ Jᵀ λ).
  virtual void refreshAfterCorrection(const ConstraintRowsJ& rows, const Eigen::VectorXd& lambda,
                                      const Eigen::VectorXd& r, Eigen::VectorXd& g) {
    (void)r;
    subtractPreconditionedJt(rows, lambda, g);
  }
};

struct ProjectedPcgScratch {
  Eigen::VectorXd r, g, p, ap, jz, lambda;
  std::vector<double> partials;  // the chunk sums of the dot products (sumChunks)
};

struct ProjectedPcgResult {
  int iterations = 0;
  bool converged = false;
};

// Where the iterations start: from the guess in x (CG: the last step's answer), or from P b (the
// direct path), which is the answer when G is A: `exact` says G is A's own factorisation and
// returns it at once, the direct solve; `preconditioned` iterates on from there (an earlier
// step's factors). Every iteration stops when the projected residual's norm in G's metric,
// r·G⁻¹r, is below tolerance² × b·P b: with G ≈ A that is the error's energy norm relative to the
// answer's, which weighs the soft modes (mass-bound, 0.002 kg) and the stiff ones (h² k, up to
// 700 N/m on the 10⁴× cloth) alike; a test on ‖r‖ against ‖A‖ ‖x‖ let the soft modes' error grow
// with the stiffness ratio, and one against ‖b‖ asked A's own factors for more digits than doubles
// hold.
enum class PcgStart { guess, preconditioned, exact };

// Solves A x = b on J x = c (x moved onto J x = c first), or stops at maxIterations. A is
// symmetric and stored whole; G must be ready (prepareRows called for these rows).
ProjectedPcgResult solveProjectedPcg(WorkerPool* pool, const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b,
                                     const ConstraintRowsJ& rows, PcgPreconditioner& g, Eigen::VectorXd& x,
                                     double tolerance, int maxIterations, ProjectedPcgScratch& w,
                                     PcgStart start = PcgStart::guess);

}  // namespace particles
