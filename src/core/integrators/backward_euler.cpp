#include "core/integrators/backward_euler.hpp"

namespace particles {

void BackwardEulerState::step(System& system, Eigen::VectorXd& y, double t, double h) {
  implicit_.step(system, y, t, h, ImplicitTarget{.eta = h}, options_.cgTolerance);
}

std::unique_ptr<IntegratorState> makeBackwardEulerState() {
  return std::make_unique<BackwardEulerState>();
}

}  // namespace particles
