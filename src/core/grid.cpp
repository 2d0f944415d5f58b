#include "core/grid.hpp"

#include <fmt/format.h>

namespace particles {

GridIndices addGrid(SystemBuilder& builder, DampedSpringForce& springs, const GridSpec& spec) {
  GridIndices g{builder.numParticles(), spec.cols, spec.rows};
  for (int r = 0; r < spec.rows; ++r) {
    for (int c = 0; c < spec.cols; ++c) {
      ParticleSpec p;
      p.pos = spec.origin + Vec2(c * spec.spacing.x(), -r * spec.spacing.y());
      p.mass = spec.mass;
      p.name = fmt::format("{}[{}][{}]", spec.name, r, c);
      builder.addParticle(p);
    }
  }

  auto connect = [&](const GridSpringFamily& family, int r0, int c0, int r1, int c1) {
    const double fromTop = spec.rows > 1 ? 0.5 * (r0 + r1) / double(spec.rows - 1) : 0.0;
    const double ks = family.ksTop + (family.ksBottom - family.ksTop) * fromTop;
    const Vec2 d((c1 - c0) * spec.spacing.x(), (r1 - r0) * spec.spacing.y());
    springs.add({Endpoint::ofParticle(g.at(r0, c0)), Endpoint::ofParticle(g.at(r1, c1)), d.norm(), ks, family.kd});
  };

  if (spec.structural) {
    for (int r = 0; r < spec.rows; ++r)
      for (int c = 0; c + 1 < spec.cols; ++c) connect(*spec.structural, r, c, r, c + 1);
    for (int r = 0; r + 1 < spec.rows; ++r)
      for (int c = 0; c < spec.cols; ++c) connect(*spec.structural, r, c, r + 1, c);
  }
  if (spec.shear) {
    for (int r = 0; r + 1 < spec.rows; ++r) {
      for (int c = 0; c + 1 < spec.cols; ++c) {
        connect(*spec.shear, r, c, r + 1, c + 1);
        connect(*spec.shear, r, c + 1, r + 1, c);
      }
    }
  }
  if (spec.flexion) {
    for (int r = 0; r < spec.rows; ++r)
      for (int c = 0; c + 2 < spec.cols; ++c) connect(*spec.flexion, r, c, r, c + 2);
    for (int r = 0; r + 2 < spec.rows; ++r)
      for (int c = 0; c < spec.cols; ++c) connect(*spec.flexion, r, c, r + 2, c);
  }
  return g;
}

long long gridSpringCount(const GridSpec& spec) {
  const long long r = spec.rows, c = spec.cols;
  auto atLeastZero = [](long long n) { return n > 0 ? n : 0; };
  long long n = 0;
  // The loops of addGrid, counted: neighbours across and down, both diagonals of each cell, and
  // neighbours two apart across and down.
  if (spec.structural) n += r * atLeastZero(c - 1) + atLeastZero(r - 1) * c;
  if (spec.shear) n += 2 * atLeastZero(r - 1) * atLeastZero(c - 1);
  if (spec.flexion) n += r * atLeastZero(c - 2) + atLeastZero(r - 2) * c;
  return n;
}

}  // namespace particles
