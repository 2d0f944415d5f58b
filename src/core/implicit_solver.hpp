#pragma once
// Which linear solve the implicit integrators (backward Euler, BDF2) use for their step's sparse
// system (core/implicit_step.hpp): a scenario's `simulation.implicit_solver`, the commands'
// --implicit-solver.

#include <optional>
#include <stdexcept>
#include <string_view>

namespace particles {

enum class ImplicitSolver {
  automatic,  // CG, then direct once a CG step costs more than the direct solve would (implicit_step.hpp)
  direct,     // sparse LDLᵀ of the step's matrix, reused across steps, refined by PCG
  cg,         // conjugate gradients with the Jacobi preconditioner
};

// The scene's implicit_solver cannot be honoured (direct with more general constraint rows than
// the Schur complement takes): bad input, named by the message, not a simulation failure.
class ImplicitSolverError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

std::string_view implicitSolverName(ImplicitSolver solver);  // "auto", "direct", "cg"
std::optional<ImplicitSolver> implicitSolverFromName(std::string_view name);

}  // namespace particles
