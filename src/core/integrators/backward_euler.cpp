#include "core/integrators/backward_euler.hpp"

namespace particles {

void integrateBackwardEuler(System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w,
                            const BackwardEulerOptions& options) {
  implicitStep(system, y, t, h, ImplicitTarget{.eta = h}, w.implicit, options.cgTolerance);
}

}  // namespace particles
