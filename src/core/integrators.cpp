#include "core/integrators.hpp"

#include <array>

namespace particles {

namespace {
constexpr std::array<Integrator, 3> kAll{Integrator::Euler, Integrator::Midpoint, Integrator::Rk4};
}

std::string_view integratorName(Integrator integrator) {
  switch (integrator) {
    case Integrator::Euler: return "euler";
    case Integrator::Midpoint: return "midpoint";
    case Integrator::Rk4: return "rk4";
  }
  return "unknown";
}

std::optional<Integrator> integratorFromName(std::string_view name) {
  for (Integrator i : kAll) {
    if (integratorName(i) == name) return i;
  }
  return std::nullopt;
}

std::span<const Integrator> allIntegrators() { return kAll; }

int derivEvalsPerStep(Integrator integrator) {
  switch (integrator) {
    case Integrator::Euler: return 1;
    case Integrator::Midpoint: return 2;
    case Integrator::Rk4: return 4;
  }
  return 0;
}

void integrateEuler(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  f(y, t, w.k1);
  y += h * w.k1;
}

void integrateMidpoint(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  f(y, t, w.k1);
  w.tmp = y + (0.5 * h) * w.k1;
  f(w.tmp, t + 0.5 * h, w.k2);
  y += h * w.k2;
}

void integrateRk4(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  // The k's here are derivatives; the h of the formula above is applied when they are combined.
  f(y, t, w.k1);
  w.tmp = y + (0.5 * h) * w.k1;
  f(w.tmp, t + 0.5 * h, w.k2);
  w.tmp = y + (0.5 * h) * w.k2;
  f(w.tmp, t + 0.5 * h, w.k3);
  w.tmp = y + h * w.k3;
  f(w.tmp, t + h, w.k4);
  y += (h / 6.0) * (w.k1 + 2.0 * w.k2 + 2.0 * w.k3 + w.k4);
}

void integrate(Integrator integrator, const DerivFn& f, Eigen::VectorXd& y, double t, double h,
               IntegratorScratch& w) {
  switch (integrator) {
    case Integrator::Euler: integrateEuler(f, y, t, h, w); return;
    case Integrator::Midpoint: integrateMidpoint(f, y, t, h, w); return;
    case Integrator::Rk4: integrateRk4(f, y, t, h, w); return;
  }
}

}  // namespace particles
