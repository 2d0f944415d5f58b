#include "core/integrators/rk4.hpp"

namespace particles {

void integrateRk4(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  // The k's here are derivatives; the h of the formula in rk4.hpp is applied when they are combined.
  f(y, t, w.k1);
  w.tmp = y + (0.5 * h) * w.k1;
  f(w.tmp, t + 0.5 * h, w.k2);
  w.tmp = y + (0.5 * h) * w.k2;
  f(w.tmp, t + 0.5 * h, w.k3);
  w.tmp = y + h * w.k3;
  f(w.tmp, t + h, w.k4);
  y += (h / 6.0) * (w.k1 + 2.0 * w.k2 + 2.0 * w.k3 + w.k4);
}

}  // namespace particles
