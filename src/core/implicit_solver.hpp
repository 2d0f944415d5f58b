#pragma once
// Which linear solve the implicit integrators (backward Euler, BDF2) use for their step's sparse
// system (core/implicit_step.hpp): a scenario's `simulation.implicit_solver`, the commands'
// --implicit-solver.

#include <optional>
#include <string_view>

namespace particles {

enum class ImplicitSolver {
  automatic,  // direct up to kAutoDirectMaxCoordinates free coordinates, else CG (measured, bench/README.md)
  direct,     // sparse LDLᵀ of the step's matrix, reused across steps, refined by PCG
  cg,         // conjugate gradients with the Jacobi preconditioner
};

std::string_view implicitSolverName(ImplicitSolver solver);  // "auto", "direct", "cg"
std::optional<ImplicitSolver> implicitSolverFromName(std::string_view name);

}  // namespace particles
