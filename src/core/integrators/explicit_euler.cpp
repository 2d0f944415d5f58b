#include "core/integrators/explicit_euler.hpp"

namespace particles {

void integrateEuler(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  f(y, t, w.k1);
  y += h * w.k1;
}

}  // namespace particles
