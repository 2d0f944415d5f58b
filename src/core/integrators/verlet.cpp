#include "core/integrators/verlet.hpp"

#include <algorithm>
#include <cmath>

namespace particles {

namespace {

// Bitwise equal: the cache is only good for exactly the state it was computed at.
bool sameState(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::equal(a.data(), a.data() + a.size(), b.data());
}

}  // namespace

void integrateVerlet(const DerivFn& f, const StateLayout& layout, Eigen::VectorXd& y, double t, double h,
                     IntegratorScratch& w) {
  // The solver computes t as t₀ + k·dt afresh each step, so the cached time may differ from it in
  // the last bits; anything further off is a jump in time.
  const bool cached = w.verletValid && std::abs(w.verletT - t) <= 1e-12 * std::max(1.0, std::abs(t)) &&
                      sameState(w.verletY, y);
  if (!cached) f(y, t, w.verletF);
  const Eigen::VectorXd& a0 = w.verletF;
  w.tmp = y;
  for (const auto& b : layout.secondOrderBlocks()) {
    const auto v0 = y.segment(b.velocity, b.length);
    const auto acc0 = a0.segment(b.velocity, b.length);
    w.tmp.segment(b.position, b.length) += h * v0 + (0.5 * h * h) * acc0;
    w.tmp.segment(b.velocity, b.length) += h * acc0;  // the prediction a₁ is evaluated at
  }
  f(w.tmp, t + h, w.k2);
  for (const auto& b : layout.secondOrderBlocks()) {
    y.segment(b.position, b.length) = w.tmp.segment(b.position, b.length);
    y.segment(b.velocity, b.length) +=
        (0.5 * h) * (a0.segment(b.velocity, b.length) + w.k2.segment(b.velocity, b.length));
  }
  w.verletF.swap(w.k2);
  w.verletY = y;
  w.verletT = t + h;
  w.verletValid = true;
}

}  // namespace particles
