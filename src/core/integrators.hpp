#pragma once
// The integrators (docs/physics.md §3) and their registry. One step advances the flat state y from
// t to t + h; every integrator reaches the system only through derivEval (and, for the implicit
// one, the force Jacobians). Each is a file pair under integrators/ with its formula at the top:
// the report's three explicit methods over a derivative f(y, t) (explicit_euler, midpoint, rk4),
// and the ones that treat positions and velocities apart (symplectic_euler, verlet,
// backward_euler).
//
// A new integrator: its file pair, an enum value below, and one row in the table of integrators.cpp.

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <array>
#include <functional>
#include <optional>
#include <span>
#include <string_view>

#include "core/constraint.hpp"
#include "core/force_jacobians.hpp"
#include "core/worker_pool.hpp"

namespace particles {

class System;

enum class Integrator { Euler, Midpoint, Rk4, SymplecticEuler, Verlet, BackwardEuler };

std::string_view integratorName(Integrator integrator);
// "euler", "midpoint", "rk4", "symplectic_euler", "verlet", "backward_euler"
std::optional<Integrator> integratorFromName(std::string_view name);
std::span<const Integrator> allIntegrators();
// Derivative evaluations a step costs once under way: 1, 2, 4, 1, 1 (Verlet reuses the previous
// step's last one), 1 (backward Euler, plus the Jacobians and a sparse solve).
int derivEvalsPerStep(Integrator integrator);
// True for the integrators after which the solver projects the state onto the constraints: their
// steps do not follow the multipliers' drift feedback the way the explicit Runge–Kutta ones do.
bool projectsConstraints(Integrator integrator);
// One line on what the integrator is, for --help and the docs.
std::string_view integratorSummary(Integrator integrator);

using DerivFn = std::function<void(const Eigen::VectorXd& y, double t, Eigen::VectorXd& dydt)>;

// Backward Euler's projected CG (integrators/backward_euler.cpp).
struct ProjectedCgScratch {
  Eigen::VectorXd dinv, c, r, g, p, ap, jz, lambda;
  std::vector<double> partials;  // the chunk sums of the dot products (sumChunks)
  std::vector<char> found;       // anyOf's chunk verdicts
  // J row by row: up to four (column, value) pairs (two particles × x, y); column −1 is unused.
  std::vector<std::array<int, 4>> rowColumns;
  std::vector<std::array<double, 4>> rowValues;
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::SparseMatrix<double> j, s;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
};

// Backward Euler's matrix pattern: the Jacobians' (row, column) keys it was built from, and
// which triplets' values go where in the compressed matrix, read so that threads fill whole
// values and rows, each summing in the triplets' order (the order a serial scatter adds in).
struct AssemblyPattern {
  bool valid = false;
  std::vector<int> dfdvKeys, dfdxKeys;
  // Per value slot, the entries that land there (k < |D|: D's k-th, else K's (k − |D|)-th) from
  // slotStart[slot], and the coordinate whose diagonal it is (−1: none); per row of K, its
  // entries' indices from kRowStart[row].
  std::vector<int> slotStart, slotEntries, slotDiagonal, kRowStart, kRowEntries;
};

// Scratch kept between steps, so stepping does not allocate, and what an integrator carries from
// one step to the next (Verlet's last evaluation, backward Euler's last Δv as CG's first guess).
struct IntegratorScratch {
  // The System's threads, for the whole-vector updates (set by integrate; null: serial).
  WorkerPool* pool = nullptr;
  Eigen::VectorXd k1, k2, k3, k4, tmp;

  // Verlet: f at (verletY, verletT), valid when verletValid.
  Eigen::VectorXd verletF, verletY;
  double verletT = 0.0;
  bool verletValid = false;
  // The solver moved y by a projection after the step (a drift-sized correction): the cached
  // evaluation stays, so Verlet keeps to one evaluation per step on constrained systems.
  void stateProjected(const Eigen::VectorXd& y) {
    if (verletValid) verletY = y;
  }

  // Backward Euler.
  ForceJacobians jacobians;
  std::vector<ConstraintRow> constraintRows;
  ProjectedCgScratch cg;
  AssemblyPattern pattern;
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::SparseMatrix<double> matrix;
  Eigen::VectorXd rhs, dv;
  int cgIterations = 0;  // of the last step, for benchmarks
};

// One step of the named integrator on the system's state y at time t.
void integrate(Integrator integrator, System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);

}  // namespace particles
