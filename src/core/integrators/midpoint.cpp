#include "core/integrators/midpoint.hpp"

namespace particles {

void integrateMidpoint(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  f(y, t, w.k1);
  w.tmp.resize(y.size());
  forSegments(w.pool, y.size(),
              [&](long i, long n) { w.tmp.segment(i, n) = y.segment(i, n) + (0.5 * h) * w.k1.segment(i, n); });
  f(w.tmp, t + 0.5 * h, w.k2);
  forSegments(w.pool, y.size(), [&](long i, long n) { y.segment(i, n) += h * w.k2.segment(i, n); });
}

std::unique_ptr<IntegratorState> makeMidpointState() {
  return makeExplicitMethodState<integrateMidpoint>();
}

}  // namespace particles
