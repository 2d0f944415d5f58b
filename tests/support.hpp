#pragma once
// Small builders and helpers shared by the physics tests.

#include <memory>

#include "core/forces/damped_spring_force.hpp"
#include "core/forces/gravity_force.hpp"
#include "core/grid.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"

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

// A square grid like the report's cloth: structural springs only, k_s 25 N/m at the top row to
// 1 N/m at the bottom, k_d 0.2, 0.05 kg per particle, row 0 at (−1, 1).
inline GridSpec reportCloth(int size, double spacing) {
  GridSpec spec;
  spec.name = "cloth";
  spec.origin = Vec2(-1, 1);
  spec.cols = size;
  spec.rows = size;
  spec.spacing = Vec2(spacing, spacing);
  spec.mass = 0.05;
  spec.structural = GridSpringFamily{25.0, 1.0, 0.2};
  return spec;
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
