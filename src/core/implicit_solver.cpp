#include "core/implicit_solver.hpp"

#include "core/name_table.hpp"

namespace particles {

namespace {

constexpr NameTableRow<ImplicitSolver> kNames[] = {
    {ImplicitSolver::automatic, "auto"},
    {ImplicitSolver::direct, "direct"},
    {ImplicitSolver::cg, "cg"},
};

}  // namespace

std::string_view implicitSolverName(ImplicitSolver solver) {
  return nameOf(kNames, solver, "auto");
}

std::optional<ImplicitSolver> implicitSolverFromName(std::string_view name) {
  return valueNamed(kNames, name);
}

}  // namespace particles
