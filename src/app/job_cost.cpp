// A sweep job's estimated cost: see job_cost.hpp.
#include "app/job_cost.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace particles::app {

namespace {

// Power iterations: the estimate approaches λ_max from below; 30 bring the 25² cloth within a few
// per cent, far closer than the ordering of jobs needs.
constexpr int kPowerIterations = 30;

// The position coordinates of the state (points' x, then bodies' θ) gathered into one vector, and
// scattered back as a displacement.
Eigen::VectorXd positionsOf(const StateLayout& layout, const Eigen::VectorXd& y, bool velocityBlocks) {
  Eigen::VectorXd out(2 * Eigen::Index(layout.numPoints()) + layout.numBodies);
  Eigen::Index at = 0;
  for (const auto& block : layout.secondOrderBlocks()) {
    out.segment(at, block.length) = y.segment(velocityBlocks ? block.velocity : block.position, block.length);
    at += block.length;
  }
  return out;
}

void displace(const StateLayout& layout, Eigen::VectorXd& y, const Eigen::VectorXd& by) {
  Eigen::Index at = 0;
  for (const auto& block : layout.secondOrderBlocks()) {
    y.segment(block.position, block.length) += by.segment(at, block.length);
    at += block.length;
  }
}

// splitmix64 (Steele, Lea & Flood 2014) of `i`, as a double in [−1, 1).
double pseudoRandom(std::uint64_t i) {
  std::uint64_t z = i + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return double(z >> 11) * 0x1.0p-52 - 1.0;
}

}  // namespace

double fastestAngularFrequency(System& system) {
  const StateLayout& layout = system.layout();
  const Eigen::VectorXd start = system.state();
  const double t = system.time();
  Eigen::VectorXd dydt(start.size());
  system.derivEval(start, t, dydt, System::ConstraintForces::skip);
  const Eigen::VectorXd startAcceleration = positionsOf(layout, dydt, true);
  if (startAcceleration.size() == 0) return 0.0;

  // A displacement small against the scene (relative 1e-6: far above rounding, far below where
  // a spring's force stops being linear in it).
  const Eigen::VectorXd startPositions = positionsOf(layout, start, false);
  const double step = 1e-6 * (1.0 + startPositions.cwiseAbs().maxCoeff());
  // A fixed pseudo-random start (splitmix64 of the index, in [−1, 1)) has a share of every mode; a
  // regular pattern may have none of the stiff ones (it may move two points as one). Fixed
  // particles stay where they are.
  Eigen::VectorXd direction(startAcceleration.size());
  for (Eigen::Index i = 0; i < direction.size(); ++i) direction[i] = pseudoRandom(std::uint64_t(i));
  const Model& model = system.model();
  for (int p = 0; p < layout.numPoints(); ++p) {
    if (model.invMass[p] == 0.0) direction.segment<2>(2 * p).setZero();
  }
  if (!(direction.norm() > 0.0)) return 0.0;
  direction.normalize();
  double lambda = 0.0;
  Eigen::VectorXd moved(start.size());
  for (int k = 0; k < kPowerIterations; ++k) {
    moved = start;
    displace(layout, moved, step * direction);
    system.derivEval(moved, t, dydt, System::ConstraintForces::skip);
    const Eigen::VectorXd response = (positionsOf(layout, dydt, true) - startAcceleration) / step;
    const double norm = response.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) break;
    lambda = norm;  // |W K u| for a unit u
    direction = response / norm;
  }
  return std::sqrt(lambda);
}

double estimatedJobCost(scenario::Scenario& s, std::string_view command) {
  const double size = double(s.system.layout().numPoints()) + double(scenario::springCount(s.system));
  const double dt = s.simulation.dt;
  if (command == "stability") {
    const double omega = fastestAngularFrequency(s.system);
    const double limit = omega > 0.0 ? 2.0 / omega : dt;
    return s.simulation.duration / std::min(dt, limit) * size;
  }
  return double(s.simulation.steps()) * derivEvalsPerStep(s.simulation.integrator) * size;
}

bool jobSpreadsOverThreads(const scenario::Scenario& s, std::string_view command) {
  return command == "stability" || command == "render" || s.system.spreadsOverThreads();
}

}  // namespace particles::app
