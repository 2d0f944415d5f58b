#include "core/integrators/rk4.hpp"

namespace particles {

void integrateRk4(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  // The k's here are derivatives; the h of the formula in rk4.hpp is applied when they are combined.
  // Each update is elementwise, so it is split over the System's threads (forSegments).
  w.tmp.resize(y.size());
  auto stage = [&](const Eigen::VectorXd& k, double scale) {
    forSegments(w.pool, y.size(),
                [&](long i, long n) { w.tmp.segment(i, n) = y.segment(i, n) + scale * k.segment(i, n); });
  };
  f(y, t, w.k1);
  stage(w.k1, 0.5 * h);
  f(w.tmp, t + 0.5 * h, w.k2);
  stage(w.k2, 0.5 * h);
  f(w.tmp, t + 0.5 * h, w.k3);
  stage(w.k3, h);
  f(w.tmp, t + h, w.k4);
  forSegments(w.pool, y.size(), [&](long i, long n) {
    y.segment(i, n) +=
        (h / 6.0) * (w.k1.segment(i, n) + 2.0 * w.k2.segment(i, n) + 2.0 * w.k3.segment(i, n) + w.k4.segment(i, n));
  });
}

std::unique_ptr<IntegratorState> makeRk4State() {
  return makeExplicitMethodState<integrateRk4>();
}

}  // namespace particles
