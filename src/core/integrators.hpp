#pragma once
// Explicit one-step integrators over a derivative function f(y, t) (docs/physics.md §3), h = dt:
//   Euler     y₁ = y₀ + h f(y₀, t₀)                                     global error O(h)
//   Midpoint  y₁ = y₀ + h f(y₀ + h/2 f(y₀, t₀), t₀ + h/2)               global error O(h²)
//   RK4       k1 = h f(y₀, t₀),         k2 = h f(y₀ + k1/2, t₀ + h/2),
//             k3 = h f(y₀ + k2/2, t₀ + h/2), k4 = h f(y₀ + k3, t₀ + h),
//             y₁ = y₀ + k1/6 + k2/3 + k3/3 + k4/6                       global error O(h⁴)

#include <functional>
#include <optional>
#include <span>
#include <string_view>

#include <Eigen/Core>

namespace particles {

enum class Integrator { Euler, Midpoint, Rk4 };

std::string_view integratorName(Integrator integrator);
std::optional<Integrator> integratorFromName(std::string_view name);  // "euler", "midpoint", "rk4"
std::span<const Integrator> allIntegrators();
int derivEvalsPerStep(Integrator integrator);  // 1, 2, 4

using DerivFn = std::function<void(const Eigen::VectorXd& y, double t, Eigen::VectorXd& dydt)>;

// Scratch vectors reused between steps, so stepping does not allocate.
struct IntegratorScratch {
  Eigen::VectorXd k1, k2, k3, k4, tmp;
};

void integrateEuler(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);
void integrateMidpoint(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);
void integrateRk4(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);
void integrate(Integrator integrator, const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);

}  // namespace particles
