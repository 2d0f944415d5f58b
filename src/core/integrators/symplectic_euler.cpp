#include "core/integrators/symplectic_euler.hpp"

#include <functional>

#include "core/system.hpp"

namespace particles {

void integrateSymplecticEuler(const DerivFn& f, const StateLayout& layout, Eigen::VectorXd& y, double t, double h,
                              IntegratorScratch& w, const VelocityProjection& projectVelocities) {
  f(y, t, w.k1);
  const auto blocks = layout.secondOrderBlocks();
  for (const auto& b : blocks) {
    forSegments(w.pool, b.length,
                [&](long i, long n) { y.segment(b.velocity + i, n) += h * w.k1.segment(b.velocity + i, n); });
  }
  if (projectVelocities) projectVelocities(y);
  for (const auto& b : blocks) {
    forSegments(w.pool, b.length,
                [&](long i, long n) { y.segment(b.position + i, n) += h * y.segment(b.velocity + i, n); });
  }
}

std::unique_ptr<IntegratorState> makeSymplecticEulerState() {
  return std::make_unique<ScratchOnlyState>(
      [](System& s, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
        const DerivFn withoutConstraintForces = [&s](const Eigen::VectorXd& at, double time, Eigen::VectorXd& dydt) {
          s.derivEval(at, time, dydt, System::ConstraintForces::skip);
        };
        VelocityProjection project;
        if (!s.constraints().empty()) project = [&s](Eigen::VectorXd& at) { s.projectVelocitiesOntoConstraints(at); };
        integrateSymplecticEuler(withoutConstraintForces, s.layout(), y, t, h, w, project);
      });
}

}  // namespace particles
