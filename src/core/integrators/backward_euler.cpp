#include "core/integrators/backward_euler.hpp"

#include <Eigen/IterativeLinearSolvers>

#include "core/system.hpp"

namespace particles {

void integrateBackwardEuler(System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w,
                            const BackwardEulerOptions& options) {
  const Model& model = system.model();
  const StateLayout& layout = model.layout;
  const Eigen::Index n = 2 * Eigen::Index(layout.numPoints());
  const Eigen::Index vOff = layout.velocityOffset();

  system.derivEval(y, t, w.k1, System::ConstraintForces::skip);  // [v₀ | f₀/m | ω₀ | τ₀/I]
  system.forceJacobians(y, t, w.jacobians);
  auto fixedDof = [&](Eigen::Index i) { return model.invMass[i / 2] == 0.0; };

  // A = M − h D − h² K over the free coordinates; a fixed one's row and column are the identity.
  w.triplets.clear();
  w.triplets.reserve(size_t(n) + w.jacobians.dfdv.size() + w.jacobians.dfdx.size());
  for (Eigen::Index i = 0; i < n; ++i) w.triplets.emplace_back(i, i, fixedDof(i) ? 1.0 : model.mass[i / 2]);
  auto addScaled = [&](const ForceJacobians::Triplets& from, double scale) {
    for (const auto& e : from) {
      if (!fixedDof(e.row()) && !fixedDof(e.col())) w.triplets.emplace_back(e.row(), e.col(), scale * e.value());
    }
  };
  addScaled(w.jacobians.dfdv, -h);
  addScaled(w.jacobians.dfdx, -h * h);
  w.matrix.resize(n, n);
  w.matrix.setFromTriplets(w.triplets.begin(), w.triplets.end());

  // b = h (f₀ + h K v₀); K v₀ straight from K's triplets.
  w.rhs.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) w.rhs[i] = model.mass[i / 2] * w.k1[vOff + i];
  for (const auto& e : w.jacobians.dfdx) w.rhs[e.row()] += h * e.value() * y[vOff + e.col()];
  w.rhs *= h;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (fixedDof(i)) w.rhs[i] = 0.0;
  }

  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(options.tolerance);
  cg.compute(w.matrix);
  if (w.dv.size() != n) w.dv.setZero(n);
  w.dv = cg.solveWithGuess(w.rhs, w.dv);
  w.cgIterations = int(cg.iterations());

  y.segment(vOff, n) += w.dv;
  if (!system.constraints().empty()) system.projectVelocitiesOntoConstraints(y);
  y.head(n) += h * y.segment(vOff, n);
  // Rotation: explicit (see the header).
  const int bodies = layout.numBodies;
  y.segment(layout.omegaOffset(), bodies) += h * w.k1.segment(layout.omegaOffset(), bodies);
  y.segment(layout.angleOffset(), bodies) += h * y.segment(layout.omegaOffset(), bodies);
}

}  // namespace particles
