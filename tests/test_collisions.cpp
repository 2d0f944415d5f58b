// Penalty collisions by numbers (docs/physics.md §6): f = n k d², U = k d³/3.
#include <doctest/doctest.h>

#include <cmath>

#include "core/colliders/disk_collider.hpp"
#include "core/forces/drag_force.hpp"
#include "core/colliders/half_plane_collider.hpp"
#include "support.hpp"

using namespace particles;
using namespace particles::test;

TEST_CASE("a point inside a half-plane or a disk has a contact with its depth and outward normal, outside none") {
  const HalfPlaneCollider ground(Vec2(0, 2), -1.5);  // normal is normalised
  CHECK(ground.normal() == Vec2(0, 1));
  CHECK_FALSE(ground.contact(Vec2(3, -1.4)).has_value());
  const auto c = ground.contact(Vec2(3, -1.6));
  REQUIRE(c.has_value());
  CHECK(c->depth == doctest::Approx(0.1));
  CHECK(c->normal == Vec2(0, 1));

  const DiskCollider disk(Vec2(1, 1), 0.5);
  CHECK_FALSE(disk.contact(Vec2(1.6, 1)).has_value());
  const auto d = disk.contact(Vec2(1, 0.6));
  REQUIRE(d.has_value());
  CHECK(d->depth == doctest::Approx(0.1));
  CHECK((d->normal - Vec2(0, -1)).norm() < 1e-15);
  CHECK(disk.contact(Vec2(1, 1))->normal == Vec2(0, 1));  // the centre has a defined way out
}

TEST_CASE("a particle 0.2 m into a half-plane feels k d² along the normal and stores k d³ / 3") {
  SystemBuilder b;
  b.addParticle(particleAt(0, -0.2));
  b.addCollider(std::make_unique<HalfPlaneCollider>(Vec2(0, 1), 0.0, PenaltyParams{1000.0, 0.0}));
  System sys = b.build();
  Eigen::VectorXd dydt;
  sys.derivEval(sys.state(), 0.0, dydt);
  CHECK(dydt[2 + 1] == doctest::Approx(1000.0 * 0.2 * 0.2));  // a = n k d² / m
  CHECK(dydt[2] == 0.0);
  CHECK(sys.energy().potential == doctest::Approx(1000.0 * 0.008 / 3.0));
  CHECK(sys.penetration(sys.state()) == doctest::Approx(0.2));
}

namespace {

System dropOnGround(double k, double damping, double height) {
  SystemBuilder b;
  b.addParticle(particleAt(0, height, 1.0));
  b.emplaceForce<GravityForce>(Vec2(0, -9.81));
  b.addCollider(std::make_unique<HalfPlaneCollider>(Vec2(0, 1), 0.0, PenaltyParams{k, damping}));
  return b.build();
}

// Runs an elastic collision of a particle against `collider` and returns the velocity after it.
Vec2 bounceOffDisk(const Vec2& start, const Vec2& velocity) {
  SystemBuilder b;
  ParticleSpec p = particleAt(start.x(), start.y());
  p.vel = velocity;
  b.addParticle(p);
  b.addCollider(std::make_unique<DiskCollider>(Vec2(0, 0), 0.3, PenaltyParams{1e5, 0.0}));
  System sys = b.build();
  Solver solver(Integrator::rk4);
  advance(sys, solver, 1e-4, 10000);  // 1 s: long past the contact
  CHECK(sys.penetration(sys.state()) == 0.0);
  return sys.view().vel(0);
}

}  // namespace

TEST_CASE("a particle dropped on a half-plane: penetration bounded by energy, then at rest") {
  const double k = 1e4, g = 9.81, m = 1.0, h = 1.0;
  {
    // Undamped: all of m g (h + d) goes into the penalty's k d³/3 at the deepest point, so
    // d_max solves k d³/3 = m g (h + d) (fixed-point iteration below); RK4 at 1 ms must hit it.
    System sys = dropOnGround(k, 0.0, h);
    Solver solver(Integrator::rk4);
    double deepest = 0.0;
    for (int s = 0; s < 1000; ++s) {
      solver.doStep(sys, 1e-3);
      deepest = std::max(deepest, sys.penetration(sys.state()));
    }
    double dMax = 0.1;
    for (int i = 0; i < 50; ++i) dMax = std::cbrt(3 * m * g * (h + dMax) / k);
    CAPTURE(dMax);
    CHECK(deepest == doctest::Approx(dMax).epsilon(0.01));
  }
  {
    // Contact damping lets it settle at the static depth √(m g / k) = 0.0313 m: c = 40 N·s/m is
    // 0.8 of critical for the linearised contact stiffness 2 k d = 626 N/m there.
    System sys = dropOnGround(k, 40.0, h);
    Solver solver(Integrator::rk4);
    advance(sys, solver, 1e-3, 5000);
    CHECK(std::abs(sys.view().vel(0).y()) < 1e-3);
    CHECK(sys.penetration(sys.state()) == doctest::Approx(std::sqrt(m * g / k)).epsilon(1e-3));
  }
}

TEST_CASE("a particle hitting a disk leaves with its normal velocity reversed") {
  // No damping: the penalty force is conservative, so the bounce is elastic.
  SUBCASE("head-on") {
    const Vec2 v = bounceOffDisk(Vec2(-1.0, 0.0), Vec2(2.0, 0.0));
    CHECK(v.x() == doctest::Approx(-2.0).epsilon(1e-6));
    CHECK(std::abs(v.y()) < 1e-12);
  }
  SUBCASE("oblique") {
    // The normal at first touch: the point of the circle at height 0.1.
    const Vec2 n = Vec2(-std::sqrt(0.3 * 0.3 - 0.1 * 0.1), 0.1).normalized();
    const Vec2 before(2.0, 0.0);
    const Vec2 v = bounceOffDisk(Vec2(-1.0, 0.1), before);
    CAPTURE(v.transpose());
    CHECK(before.dot(n) < 0.0);
    CHECK(v.dot(n) > 0.0);
    CHECK(v.norm() == doctest::Approx(2.0).epsilon(1e-6));  // elastic: speed is kept
    CHECK(v.y() > 0.0);  // deflected upwards, away from the disk
  }
}

namespace {

struct ContactReadings {
  Vec2 force;          // what applyCollisions adds to the particle, N
  double potential;    // collision energy, J
  double penetration;  // System::penetration, m
};

// One particle at rest `depth` below the ground y = 0, fixed or free: what the collision code
// reports for it. The force is read from applyCollisions directly: derivEval multiplies it by
// the inverse mass, which is 0 for a fixed particle, and would hide it.
ContactReadings particleBelowGround(double depth, double k, bool fixed) {
  SystemBuilder b;
  b.addParticle(particleAt(0.3, -depth, 1.0, fixed));
  b.addCollider(std::make_unique<HalfPlaneCollider>(Vec2(0, 1), 0.0, PenaltyParams{k, 2.0}));
  const System sys = b.build();
  ForceAccumulator acc;
  acc.resize(sys.layout());
  applyCollisions(sys.model(), sys.view(), sys.colliders(), acc);
  return {acc.forceOn(0), sys.energy().potential, sys.penetration(sys.state())};
}

}  // namespace

TEST_CASE("a fixed particle inside a collider feels no force, stores no energy and is no contact") {
  // A fixed particle cannot respond to the penalty force, so it stores none of its energy, and
  // its depth is not a contact: force, potential and penetration agree on skipping it. A free
  // particle at the same place gets f = n k d², U = k d³/3 and depth d (the damping term is 0
  // at rest). Approx's default 1e-5 relative: the values are a few roundings from exact.
  const double k = 1000.0, d = 0.2;
  const ContactReadings free = particleBelowGround(d, k, false);
  CAPTURE(free.force.transpose());
  CAPTURE(free.potential);
  CAPTURE(free.penetration);
  CHECK(free.force.x() == 0.0);
  CHECK(free.force.y() == doctest::Approx(k * d * d));
  CHECK(free.potential == doctest::Approx(k * d * d * d / 3.0));
  CHECK(free.penetration == doctest::Approx(d));

  const ContactReadings fixed = particleBelowGround(d, k, true);
  CAPTURE(fixed.force.transpose());
  CAPTURE(fixed.potential);
  CAPTURE(fixed.penetration);
  CHECK(fixed.force.norm() == 0.0);
  CHECK(fixed.potential == 0.0);
  CHECK(fixed.penetration == 0.0);
}
