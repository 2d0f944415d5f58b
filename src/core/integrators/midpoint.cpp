#include "core/integrators/midpoint.hpp"

namespace particles {

void integrateMidpoint(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  f(y, t, w.k1);
  w.tmp = y + (0.5 * h) * w.k1;
  f(w.tmp, t + 0.5 * h, w.k2);
  y += h * w.k2;
}

}  // namespace particles
