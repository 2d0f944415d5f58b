// Rigid rectangles by numbers (docs/physics.md §7).
#include <doctest/doctest.h>

#include <cmath>

#include "core/colliders/half_plane_collider.hpp"
#include "core/rigid_body.hpp"
#include "support.hpp"

using namespace particles;
using namespace particles::test;

TEST_CASE("rectangle inertia matches a numerical area integral") {
  // I = ∫∫ ρ (x² + y²) dA over the rectangle, midpoint rule on a 400 × 400 grid.
  for (const Vec2& size : {Vec2(0.4, 0.1), Vec2(1.0, 1.0), Vec2(2.0, 0.3)}) {
    const double mass = 2.5;
    const int n = 400;
    const double rho = mass / (size.x() * size.y());
    const double dx = size.x() / n, dy = size.y() / n;
    double integral = 0.0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const double x = -size.x() / 2 + (i + 0.5) * dx, y = -size.y() / 2 + (j + 0.5) * dy;
        integral += rho * (x * x + y * y) * dx * dy;
      }
    }
    CAPTURE(size.transpose());
    CHECK(std::abs(rectangleInertia(mass, size) - integral) / integral < 1e-3);
  }
}

namespace {

RigidBodySpec sampleBody(double angle, double omega) {
  RigidBodySpec body;
  body.pos = Vec2(0.5, -0.25);
  body.vel = Vec2(0.3, 0.1);
  body.angle = angle;
  body.omega = omega;
  body.size = Vec2(0.8, 0.2);
  body.mass = 2.0;
  return body;
}

System oneBody(double angle, double omega) {
  SystemBuilder b;
  b.addRigidBody(sampleBody(angle, omega));
  return b.build();
}

}  // namespace

TEST_CASE("an off-centre force gives the torque r'x fy - r'y fx") {
  System sys = oneBody(0.7, 0.0);
  const Endpoint anchor = Endpoint::ofBody(0, Vec2(0.3, 0.05));
  const Vec2 f(1.5, -2.0);
  ForceAccumulator acc;
  acc.resize(sys.layout());
  applyForceAt(sys.view(), anchor, f, acc);
  const Vec2 r = Vec2(std::cos(0.7) * 0.3 - std::sin(0.7) * 0.05, std::sin(0.7) * 0.3 + std::cos(0.7) * 0.05);
  CHECK((worldOffset(sys.view(), anchor) - r).norm() < 1e-15);
  CHECK(acc.forceOn(0) == f);
  CHECK(acc.torque[0] == doctest::Approx(r.x() * f.y() - r.y() * f.x()).epsilon(1e-14));
}

TEST_CASE("a spring at an anchor, through derivEval: d/dt [x, v, theta, omega] = [v, F/m, omega, tau/I]") {
  // A 0.8 × 0.2 m, 2 kg body turning at ω = 1.3 rad/s, held at the anchor r = (0.3, 0.05) by a
  // spring (rest 0.4 m, k_s 50 N/m, no damping) to a fixed particle at (0, 0.6). Expected values
  // from the formulas, not from endpoint.cpp.
  const RigidBodySpec body = sampleBody(0.7, 1.3);
  const double rest = 0.4, ks = 50.0;
  const Vec2 anchor(0.3, 0.05), hook(0.0, 0.6);
  SystemBuilder b;
  const int j = b.addRigidBody(body);
  const int fixed = b.addParticle(particleAt(hook.x(), hook.y(), 1.0, true));
  b.emplaceForce<DampedSpringForce>().add({Endpoint::ofBody(j, anchor), Endpoint::ofParticle(fixed), rest, ks, 0.0});
  System sys = b.build();
  Eigen::VectorXd dydt;
  sys.derivEval(sys.state(), 0.0, dydt);

  // r′ = R(θ) r; the spring pulls the anchor towards the hook: f = −k_s (|l| − rest) l/|l|.
  const double c = std::cos(body.angle), sn = std::sin(body.angle);
  const Vec2 r(c * anchor.x() - sn * anchor.y(), sn * anchor.x() + c * anchor.y());
  const Vec2 l = body.pos + r - hook;
  const Vec2 f = -ks * (l.norm() - rest) * l.normalized();
  const double torque = r.x() * f.y() - r.y() * f.x();
  const double inertia = body.mass * (body.size.x() * body.size.x() + body.size.y() * body.size.y()) / 12.0;
  const StateLayout& layout = sys.layout();
  const int p = layout.bodyPoint(j);
  const Vec2 dx(dydt[2 * p], dydt[2 * p + 1]);
  const Vec2 dv(dydt[layout.velocityOffset() + 2 * p], dydt[layout.velocityOffset() + 2 * p + 1]);
  const double dTheta = dydt[layout.angleOffset() + j], dOmega = dydt[layout.omegaOffset() + j];
  CAPTURE(f.transpose());
  CAPTURE(torque);
  CAPTURE(inertia);
  CAPTURE(dv.transpose());
  CAPTURE(dOmega);
  // The spring is stretched (|l| = 0.93 m against 0.4) and pulls nearly at right angles to r′:
  // a real force and torque, so the checks below are not comparisons of zeros.
  REQUIRE(f.norm() > 10.0);
  REQUIRE(std::abs(torque) > 1.0);
  // A few roundings apart: 1e-12 relative.
  CHECK((dx - body.vel).norm() < 1e-15);
  CHECK((dv - f / body.mass).norm() < 1e-12 * f.norm() / body.mass);
  CHECK(dTheta == body.omega);
  CHECK(dOmega == doctest::Approx(torque / inertia).epsilon(1e-12));
  // The fixed hook stays put.
  CHECK(Vec2(dydt[2 * fixed], dydt[2 * fixed + 1]).norm() == 0.0);
  CHECK(Vec2(dydt[layout.velocityOffset() + 2 * fixed], dydt[layout.velocityOffset() + 2 * fixed + 1]).norm() == 0.0);
}

TEST_CASE("anchor velocity formula matches finite differences of its position") {
  System sys = oneBody(0.4, 1.3);
  const Endpoint anchor = Endpoint::ofBody(0, Vec2(-0.35, 0.08));
  const double eps = 1e-6;
  Eigen::VectorXd dydt;
  sys.derivEval(sys.state(), 0.0, dydt);  // no forces: dydt is [v, 0, ω, 0]
  const Eigen::VectorXd plus = sys.state() + eps * dydt;
  const Eigen::VectorXd minus = sys.state() - eps * dydt;
  const Vec2 fd = (endpointPosition(StateView(sys.layout(), plus), anchor) -
                   endpointPosition(StateView(sys.layout(), minus), anchor)) / (2 * eps);
  CHECK((endpointVelocity(sys.view(), anchor) - fd).norm() < 1e-8);
}

namespace {

// Σ m v and Σ (m x × v + I ω): linear and angular momentum about the origin (orbital + spin).
std::pair<Vec2, double> momentum(const System& sys) {
  Vec2 linear = Vec2::Zero();
  double angular = 0.0;
  const StateView s = sys.view();
  for (int j = 0; j < sys.layout().numBodies; ++j) {
    const int p = sys.layout().bodyPoint(j);
    const double m = sys.model().mass[p];
    linear += m * s.vel(p);
    angular += m * (s.pos(p).x() * s.vel(p).y() - s.pos(p).y() * s.vel(p).x());
    angular += sys.model().bodies[size_t(j)].inertia * s.omega(j);
  }
  return {linear, angular};
}

}  // namespace

TEST_CASE("two rigid bodies joined by a spring conserve linear and angular momentum") {
  SystemBuilder b;
  RigidBodySpec a;
  a.pos = Vec2(-0.6, 0.1);
  a.vel = Vec2(0.2, 0.5);
  a.angle = 0.3;
  a.omega = 1.0;
  a.size = Vec2(0.5, 0.15);
  a.mass = 1.0;
  RigidBodySpec c = a;
  c.pos = Vec2(0.7, -0.2);
  c.vel = Vec2(-0.1, -0.2);
  c.angle = -0.5;
  c.omega = -2.0;
  c.size = Vec2(0.3, 0.3);
  c.mass = 2.0;
  const int ia = b.addRigidBody(a), ic = b.addRigidBody(c);
  b.emplaceForce<DampedSpringForce>().add(
      {Endpoint::ofBody(ia, Vec2(0.25, 0.075)), Endpoint::ofBody(ic, Vec2(-0.15, 0.15)), 0.8, 40.0, 0.5});
  System sys = b.build();
  const auto [p0, l0] = momentum(sys);
  Solver solver(Integrator::rk4);
  double worstLinear = 0.0, worstAngular = 0.0;
  for (int s = 0; s < 10000; ++s) {  // h = 0.001, 10 s
    solver.doStep(sys, 1e-3);
    const auto [p, l] = momentum(sys);
    worstLinear = std::max(worstLinear, (p - p0).norm() / p0.norm());
    worstAngular = std::max(worstAngular, std::abs(l - l0) / std::abs(l0));
  }
  CAPTURE(worstLinear);
  CAPTURE(worstAngular);
  CHECK(worstLinear < 1e-6);
  CHECK(worstAngular < 1e-6);
  // The bodies really interacted: the spin of each changed.
  CHECK(std::abs(sys.view().omega(0) - 1.0) > 0.1);
}

TEST_CASE("a rigid rectangle falling on the ground lands on its corners and tips over") {
  SystemBuilder b;
  RigidBodySpec box;
  box.pos = Vec2(0, 0.5);
  box.angle = 0.3;
  box.size = Vec2(0.6, 0.2);
  box.mass = 1.0;
  b.addRigidBody(box);
  b.emplaceForce<GravityForce>(Vec2(0, -9.81));
  b.addCollider(std::make_unique<HalfPlaneCollider>(Vec2(0, 1), 0.0, PenaltyParams{1e5, 20.0}));
  System sys = b.build();
  Solver solver(Integrator::rk4);
  double deepest = 0.0;
  for (int s = 0; s < 4000; ++s) {
    solver.doStep(sys, 5e-4);
    deepest = std::max(deepest, sys.penetration(sys.state()));
  }
  // Corner contacts produce torque: it ends lying flat (angle a multiple of π/2's flat side),
  // resting with its centre half a height above the ground.
  const double angle = std::remainder(sys.view().angle(0), M_PI);
  CAPTURE(angle);
  CAPTURE(deepest);
  CHECK(std::abs(angle) < 0.01);
  CHECK(sys.view().pos(0).y() == doctest::Approx(0.1).epsilon(0.1));
  CHECK(deepest < 0.05);
}
