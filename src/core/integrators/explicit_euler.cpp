#include "core/integrators/explicit_euler.hpp"

namespace particles {

void integrateEuler(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  f(y, t, w.k1);
  forSegments(w.pool, y.size(), [&](long i, long n) { y.segment(i, n) += h * w.k1.segment(i, n); });
}

std::unique_ptr<IntegratorState> makeEulerState() {
  return makeExplicitMethodState<integrateEuler>();
}

}  // namespace particles
