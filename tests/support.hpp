#pragma once
// Small builders and helpers shared by the physics tests.

#include <memory>

#include "damped_spring_force.hpp"
#include "gravity_force.hpp"
#include "solver.hpp"
#include "system.hpp"

namespace particles::test {

// Runs `steps` steps of size h.
inline void advance(System& system, Solver& solver, double h, long steps) {
  for (long i = 0; i < steps; ++i) solver.doStep(system, h);
}

inline ParticleSpec particleAt(double x, double y, double mass = 1.0, bool fixed = false) {
  ParticleSpec p;
  p.pos = Vec2(x, y);
  p.mass = mass;
  p.fixed = fixed;
  return p;
}

// Undamped 1-D harmonic oscillator: a unit mass on a spring (k, rest 1) to a fixed anchor at the
// origin, released from x = 1 + amplitude at rest. x(t) = 1 + A cos(ω t), ω = √k.
inline System harmonicOscillator(double k, double amplitude) {
  SystemBuilder b;
  const int anchor = b.addParticle(particleAt(0, 0, 1.0, true));
  const int bob = b.addParticle(particleAt(1.0 + amplitude, 0));
  b.emplaceForce<DampedSpringForce>().add(
      {Endpoint::ofParticle(bob), Endpoint::ofParticle(anchor), 1.0, k, 0.0});
  return b.build();
}

}  // namespace particles::test
