#include "core/implicit_solver.hpp"

#include <array>
#include <utility>

namespace particles {

namespace {

constexpr std::array<std::pair<ImplicitSolver, std::string_view>, 3> kNames{{
    {ImplicitSolver::automatic, "auto"},
    {ImplicitSolver::direct, "direct"},
    {ImplicitSolver::cg, "cg"},
}};

}  // namespace

std::string_view implicitSolverName(ImplicitSolver solver) {
  for (const auto& [id, name] : kNames) {
    if (id == solver) return name;
  }
  return "auto";
}

std::optional<ImplicitSolver> implicitSolverFromName(std::string_view name) {
  for (const auto& [id, n] : kNames) {
    if (n == name) return id;
  }
  return std::nullopt;
}

}  // namespace particles
