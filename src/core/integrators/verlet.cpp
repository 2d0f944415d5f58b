#include "core/integrators/verlet.hpp"

#include <algorithm>
#include <cmath>

#include "core/system.hpp"

namespace particles {

namespace {

// Bitwise equal: the cache is only good for exactly the state it was computed at.
bool sameState(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::equal(a.data(), a.data() + a.size(), b.data());
}

}  // namespace

void VerletState::step(System& system, Eigen::VectorXd& y, double t, double h) {
  scratch_.pool = system.pool();
  stepWith(derivativeOf(system), system.layout(), y, t, h);
}

void VerletState::stepWith(const DerivFn& f, const StateLayout& layout, Eigen::VectorXd& y, double t, double h) {
  IntegratorScratch& w = scratch_;
  // The solver computes t as t₀ + k·dt afresh each step, so the cached time may differ from it in
  // the last bits; anything further off is a jump in time.
  const bool cached = cached_ && std::abs(lastT_ - t) <= 1e-12 * std::max(1.0, std::abs(t)) && sameState(lastY_, y);
  if (!cached) f(y, t, lastF_);
  const Eigen::VectorXd& a0 = lastF_;
  w.tmp.resize(y.size());
  for (const auto& b : layout.secondOrderBlocks()) {
    forSegments(w.pool, b.length, [&](long i, long n) {
      const auto v0 = y.segment(b.velocity + i, n);
      const auto acc0 = a0.segment(b.velocity + i, n);
      w.tmp.segment(b.position + i, n) = y.segment(b.position + i, n) + (h * v0 + (0.5 * h * h) * acc0);
      w.tmp.segment(b.velocity + i, n) = v0 + h * acc0;  // the prediction a₁ is evaluated at
    });
  }
  f(w.tmp, t + h, w.k2);
  for (const auto& b : layout.secondOrderBlocks()) {
    forSegments(w.pool, b.length, [&](long i, long n) {
      y.segment(b.position + i, n) = w.tmp.segment(b.position + i, n);
      y.segment(b.velocity + i, n) += (0.5 * h) * (a0.segment(b.velocity + i, n) + w.k2.segment(b.velocity + i, n));
    });
  }
  lastF_.swap(w.k2);
  lastY_.resize(y.size());
  forSegments(w.pool, y.size(), [&](long i, long n) { lastY_.segment(i, n) = y.segment(i, n); });
  lastT_ = t + h;
  cached_ = true;
}

void VerletState::stateProjected(const Eigen::VectorXd& y) {
  if (cached_) lastY_ = y;
}

std::unique_ptr<IntegratorState> makeVerletState() {
  return std::make_unique<VerletState>();
}

}  // namespace particles
