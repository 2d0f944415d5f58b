// Force objects by numbers (docs/physics.md §4): conservative parts against −∇U, damping along the spring,
// drag, the scripted mouse path, energy bookkeeping by source, grid generation.
#include <doctest/doctest.h>

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>

#include "core/forces/drag_force.hpp"
#include "core/grid.hpp"
#include "core/colliders/disk_collider.hpp"
#include "core/colliders/half_plane_collider.hpp"
#include "core/forces/mouse_spring_force.hpp"
#include "support.hpp"

using namespace particles;
using namespace particles::test;

namespace {

// −∂U/∂q by central differences over every position coordinate (particles and body centres) and
// every angle, compared with the accumulated forces and torques of a state with zero velocity.
void checkForceIsMinusGradient(System& sys, double t) {
  Eigen::VectorXd y = sys.state();
  const StateLayout& layout = sys.layout();
  y.segment(layout.velocityOffset(), 2 * layout.numPoints()).setZero();
  y.segment(layout.omegaOffset(), layout.numBodies).setZero();
  Eigen::VectorXd dydt;
  sys.derivEval(y, t, dydt);
  const double eps = 1e-6;
  auto gradient = [&](Eigen::Index k) {
    Eigen::VectorXd plus = y, minus = y;
    plus[k] += eps;
    minus[k] -= eps;
    return (sys.energy(plus, t).potential - sys.energy(minus, t).potential) / (2 * eps);
  };
  for (int p = 0; p < layout.numPoints(); ++p) {
    if (sys.model().invMass[p] == 0.0) continue;
    for (int d = 0; d < 2; ++d) {
      const double force = dydt[layout.velocityOffset() + 2 * p + d] * sys.model().mass[p];
      CAPTURE(p);
      CAPTURE(d);
      CHECK(force == doctest::Approx(-gradient(2 * p + d)).epsilon(1e-6).scale(1.0));
    }
  }
  for (int j = 0; j < layout.numBodies; ++j) {
    const double torque = dydt[layout.omegaOffset() + j] * sys.model().bodies[size_t(j)].inertia;
    CHECK(torque == doctest::Approx(-gradient(layout.angleOffset() + j)).epsilon(1e-6).scale(1.0));
  }
}

}  // namespace

TEST_CASE("conservative forces are minus the gradient of their potential") {
  SystemBuilder b;
  const int p0 = b.addParticle(particleAt(0.1, 0.2, 0.5));
  const int p1 = b.addParticle(particleAt(0.9, -0.3, 1.5));
  const int anchor = b.addParticle(particleAt(0, 1, 1.0, true));
  RigidBodySpec body;
  body.pos = Vec2(-0.5, -0.4);
  body.angle = 0.4;
  body.size = Vec2(0.6, 0.2);
  body.mass = 2.0;
  const int j = b.addRigidBody(body);
  auto& springs = b.emplaceForce<DampedSpringForce>();
  springs.add({Endpoint::ofParticle(p0), Endpoint::ofParticle(p1), 0.7, 30.0, 0.0});
  springs.add({Endpoint::ofParticle(p0), Endpoint::ofParticle(anchor), 0.5, 12.0, 0.0});
  springs.add({Endpoint::ofParticle(p1), Endpoint::ofBody(j, Vec2(0.3, 0.1)), 0.2, 20.0, 0.0});
  b.emplaceForce<GravityForce>(Vec2(0.5, -9.81));
  b.addForce(std::make_unique<MouseSpringForce>(MouseScript{Endpoint::ofBody(j, Vec2(-0.3, -0.1)), 0.0, 2.0,
                                                            {Vec2(0, 0), Vec2(1, 1)}, 15.0}));
  // Both a particle and a corner of the body are in the ground.
  b.addCollider(std::make_unique<HalfPlaneCollider>(Vec2(0.1, 1), -0.35, PenaltyParams{500.0, 0.0}));
  System sys = b.build();
  CHECK(sys.penetration(sys.state()) > 0.0);
  checkForceIsMinusGradient(sys, 0.7);
}

TEST_CASE("spring damping acts along the spring only") {
  // Relative velocity perpendicular to the spring produces no force; along it, k_d l̇·l/|l|.
  SystemBuilder b;
  ParticleSpec a = particleAt(0, 0);
  a.vel = Vec2(0.3, 2.0);  // 0.3 along the spring, 2.0 across it
  const int ia = b.addParticle(a);
  const int ib = b.addParticle(particleAt(1, 0, 1.0, true));
  b.emplaceForce<DampedSpringForce>().add({Endpoint::ofParticle(ia), Endpoint::ofParticle(ib), 1.0, 100.0, 4.0});
  System sys = b.build();
  Eigen::VectorXd dydt;
  sys.derivEval(sys.state(), 0.0, dydt);
  // l = xa − xb = (−1, 0), l̇ = (0.3, 2): f_a = −[0 + 4 · (−0.3)/1] (−1, 0) = (−1.2, 0).
  CHECK(dydt[4] == doctest::Approx(-1.2));
  CHECK(dydt[5] == doctest::Approx(0.0));
}

TEST_CASE("drag opposes velocity") {
  SystemBuilder b;
  ParticleSpec p = particleAt(0, 0, 2.0);
  p.vel = Vec2(1.0, -3.0);
  b.addParticle(p);
  RigidBodySpec body;
  body.omega = 2.0;
  body.vel = Vec2(0.5, 0);
  b.addRigidBody(body);
  b.emplaceForce<DragForce>(0.5, 0.1);
  System sys = b.build();
  Eigen::VectorXd dydt;
  sys.derivEval(sys.state(), 0.0, dydt);
  const Eigen::Index acc = sys.layout().velocityOffset();
  CHECK(dydt[acc] == doctest::Approx(-0.5 * 1.0 / 2.0));
  CHECK(dydt[acc + 1] == doctest::Approx(0.5 * 3.0 / 2.0));
  CHECK(dydt[acc + 2] == doctest::Approx(-0.5 * 0.5 / 1.0));
  CHECK(dydt[sys.layout().omegaOffset()] == doctest::Approx(-0.1 * 2.0 / sys.model().bodies[0].inertia));
  CHECK(sys.energy().potential == 0.0);
}

TEST_CASE("scripted mouse: target moves along the path at constant speed, only while active") {
  const MouseSpringForce mouse(
      MouseScript{Endpoint::ofParticle(0), 1.0, 3.0, {Vec2(0, 0), Vec2(3, 0), Vec2(3, 1)}, 10.0});
  CHECK(mouse.target(0.0) == Vec2(0, 0));
  CHECK(mouse.target(1.0) == Vec2(0, 0));
  CHECK((mouse.target(2.0) - Vec2(2, 0)).norm() < 1e-15);  // half of the 4 m arc length
  CHECK((mouse.target(2.75) - Vec2(3, 0.5)).norm() < 1e-15);
  CHECK(mouse.target(5.0) == Vec2(3, 1));
  CHECK_FALSE(mouse.activeAt(0.99));
  CHECK(mouse.activeAt(1.0));
  CHECK_FALSE(mouse.activeAt(3.0));

  SystemBuilder b;
  b.addParticle(particleAt(0.5, 0.5, 2.0));
  b.addForce(std::make_unique<MouseSpringForce>(mouse.script()));
  System sys = b.build();
  Eigen::VectorXd dydt;
  sys.derivEval(sys.state(), 2.0, dydt);  // target (2, 0): f = −10 ((0.5, 0.5) − (2, 0))
  CHECK(dydt[2] == doctest::Approx(10 * 1.5 / 2.0));
  CHECK(dydt[3] == doctest::Approx(-10 * 0.5 / 2.0));
  sys.derivEval(sys.state(), 3.5, dydt);  // released
  CHECK(dydt[2] == 0.0);
  CHECK_THROWS_AS(MouseSpringForce(MouseScript{Endpoint::ofParticle(0), 0, 1, {}, 1}), std::invalid_argument);
}

TEST_CASE("energy is booked by source") {
  SystemBuilder b;
  ParticleSpec p = particleAt(0, 2.0, 2.0);
  p.vel = Vec2(3.0, 0);
  const int i = b.addParticle(p);
  const int anchor = b.addParticle(particleAt(0, 3.0, 1.0, true));
  b.emplaceForce<GravityForce>(Vec2(0, -10));
  b.emplaceForce<DragForce>(0.1);
  b.emplaceForce<DampedSpringForce>().add({Endpoint::ofParticle(i), Endpoint::ofParticle(anchor), 0.5, 8.0, 1.0});
  System sys = b.build();
  const EnergyReport e = sys.energy();
  CHECK(e.kinetic == doctest::Approx(0.5 * 2.0 * 9.0));
  REQUIRE(e.potentialBySource.size() == 2);  // drag stores nothing and is not listed
  CHECK(e.potentialBySource[0].kind == "gravity");
  CHECK(e.potentialBySource[0].energy == doctest::Approx(-2.0 * (-10.0 * 2.0)));  // −m g·x
  CHECK(e.potentialBySource[1].kind == "spring");
  CHECK(e.potentialBySource[1].energy == doctest::Approx(0.5 * 8.0 * 0.25));
  CHECK(e.total() == doctest::Approx(9.0 + 40.0 + 1.0));
}

TEST_CASE("grids: particle and spring counts, positions, names and graded stiffness") {
  SystemBuilder b;
  auto& springs = b.emplaceForce<DampedSpringForce>();
  const GridSpec spec = reportCloth(25, 0.08);
  const GridIndices g = addGrid(b, springs, spec);
  CHECK(b.numParticles() == 625);
  CHECK(springs.size() == 2 * 25 * 24);  // the report's cloth
  CHECK(g.at(24, 12) == 24 * 25 + 12);
  System sys = b.build();
  CHECK(sys.model().particleNames[size_t(g.at(3, 4))] == "cloth[3][4]");
  CHECK((sys.view().pos(g.at(2, 3)) - Vec2(-1 + 3 * 0.08, 1 - 2 * 0.08)).norm() < 1e-15);
  // Horizontal springs in the top row are the stiffest, the bottom row's the softest.
  CHECK(springs.spring(0).ks == doctest::Approx(25.0));
  CHECK(springs.spring(24 * 24).ks == doctest::Approx(1.0));  // first spring of row 24
  CHECK(springs.spring(0).rest == doctest::Approx(0.08));

  SystemBuilder b2;
  auto& all = b2.emplaceForce<DampedSpringForce>();
  GridSpec small = spec;
  small.cols = 4;
  small.rows = 3;
  small.structural = GridSpringFamily{5, 5, 0};
  small.shear = GridSpringFamily{5, 5, 0};
  small.flexion = GridSpringFamily{5, 5, 0};
  addGrid(b2, all, small);
  // structural 3·3 + 2·4 = 17, shear 2·2·3 = 12, flexion 3·2 + 1·4 = 10
  CHECK(all.size() == 17 + 12 + 10);
  CHECK(all.spring(17).rest == doctest::Approx(0.08 * std::sqrt(2.0)));
}

namespace {

Eigen::MatrixXd denseOf(const ForceJacobians::Triplets& t, Eigen::Index n) {
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  return Eigen::MatrixXd(m);
}

struct JacobiansAndDifferences {
  Eigen::MatrixXd k, d;          // from the forces' addJacobians
  Eigen::MatrixXd kFd, dFd;      // central differences of the accumulated force (m · dv/dt)
};

// Every point must be free (a fixed point's force is not in dv/dt).
JacobiansAndDifferences jacobiansAt(System& sys, const Eigen::VectorXd& y, double t) {
  const StateLayout& layout = sys.layout();
  const Eigen::Index n = 2 * Eigen::Index(layout.numPoints()), v = layout.velocityOffset();
  auto force = [&](const Eigen::VectorXd& at) {
    Eigen::VectorXd dydt;
    sys.derivEval(at, t, dydt);
    Eigen::VectorXd f(n);
    for (Eigen::Index i = 0; i < n; ++i) f[i] = dydt[v + i] * sys.model().mass[i / 2];
    return f;
  };
  JacobiansAndDifferences out;
  ForceJacobians jac;
  sys.forceJacobians(y, t, jac);
  const ForceJacobians all = jac.expanded();
  out.k = denseOf(all.dfdx, n);
  out.d = denseOf(all.dfdv, n);
  out.kFd.resize(n, n);
  out.dFd.resize(n, n);
  const double eps = 1e-7;
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index offset : {Eigen::Index(0), v}) {
      Eigen::VectorXd plus = y, minus = y;
      plus[offset + j] += eps;
      minus[offset + j] -= eps;
      (offset == 0 ? out.kFd : out.dFd).col(j) = (force(plus) - force(minus)) / (2 * eps);
    }
  }
  return out;
}

double largestEigenvalue(const Eigen::MatrixXd& m) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m).eigenvalues().maxCoeff();
}

}  // namespace

TEST_CASE("a Jacobian pair's four blocks by BlockRef: (a, a) and (b, b) add its block, (a, b) and (b, a) subtract it") {
  // Two pairs over five points, their blocks placed through BlockRef, against expanded()'s
  // triplets of the same pairs.
  ForceJacobians jac;
  jac.pairs.emplace_back(3, 1, Eigen::Matrix2d{{-2.0, 0.5}, {0.5, -3.0}}, Eigen::Matrix2d{{-0.25, 0.0}, {0.0, -0.5}});
  jac.pairs.emplace_back(0, 4, Eigen::Matrix2d{{-7.0, -1.5}, {-1.5, -11.0}}, Eigen::Matrix2d::Zero());
  const Eigen::Index n = 10;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (int q = 0; q < int(jac.pairs.size()); ++q) {
    const JacobianPair& pair = jac.pairs[size_t(q)];
    const Eigen::Matrix2d block{{pair.k[0], pair.k[1]}, {pair.k[1], pair.k[2]}};
    for (BlockRef::Role role : BlockRef::kRoles) {
      const BlockRef ref{q, role};
      k.block(2 * ref.rowPoint(pair), 2 * ref.colPoint(pair), 2, 2) += ref.sign() * block;
    }
  }
  CHECK(k == denseOf(jac.expanded().dfdx, n));
  const JacobianPair& first = jac.pairs[0];
  CHECK(BlockRef{0, BlockRef::Role::ab}.rowPoint(first) == 3);
  CHECK(BlockRef{0, BlockRef::Role::ab}.colPoint(first) == 1);
  CHECK(BlockRef{0, BlockRef::Role::ba}.rowPoint(first) == 1);
  CHECK(BlockRef{0, BlockRef::Role::ba}.colPoint(first) == 3);
}

TEST_CASE("force Jacobians for backward Euler match finite differences") {
  SUBCASE("a stretched damped spring, drag and an active mouse") {
    SystemBuilder b;
    ParticleSpec p0 = particleAt(0.1, 0.2), p1 = particleAt(1.3, 0.9, 2.0), p2 = particleAt(-0.4, 1.5, 0.5);
    p1.vel = Vec2(0.3, -0.2);
    const int a = b.addParticle(p0), c = b.addParticle(p1), e = b.addParticle(p2);
    auto& springs = b.emplaceForce<DampedSpringForce>();
    springs.add({Endpoint::ofParticle(a), Endpoint::ofParticle(c), 0.9, 40.0, 0.0});  // stretched: |l| = 1.39
    springs.add({Endpoint::ofParticle(c), Endpoint::ofParticle(e), 1.0, 25.0, 0.7});
    b.emplaceForce<DragForce>(0.3);
    b.emplaceForce<MouseSpringForce>(MouseScript{Endpoint::ofParticle(e), 0.0, 1.0, {Vec2(0, 0), Vec2(1, 1)}, 15.0});
    b.emplaceForce<GravityForce>(Vec2(0, -9.81));
    System sys = b.build();
    // ∂f/∂v is exact at any velocity (f is linear in v); ∂f/∂x leaves out the damping's
    // dependence on position by design, which vanishes at rest: compare K there.
    const JacobiansAndDifferences moving = jacobiansAt(sys, sys.state(), 0.5);
    CHECK((moving.d - moving.dFd).norm() < 1e-6 * moving.d.norm());
    CHECK(moving.d.norm() > 0.3);
    Eigen::VectorXd atRest = sys.state();
    atRest.segment(sys.layout().velocityOffset(), 6).setZero();
    const JacobiansAndDifferences j = jacobiansAt(sys, atRest, 0.5);
    CHECK((j.k - j.kFd).norm() < 1e-5 * j.k.norm());
    CHECK((j.k - j.k.transpose()).norm() == 0.0);
    CHECK(largestEigenvalue(j.k) <= 1e-12);
    CHECK(largestEigenvalue(j.d) <= 1e-12);
  }
  SUBCASE("undamped springs at rest: exact where stretched, the compressive part clamped") {
    SystemBuilder b;
    const int a = b.addParticle(particleAt(0.0, 0.0)), c = b.addParticle(particleAt(1.2, 0.5));
    const int e = b.addParticle(particleAt(1.5, 1.0));
    auto& springs = b.emplaceForce<DampedSpringForce>();
    springs.add({Endpoint::ofParticle(a), Endpoint::ofParticle(c), 1.0, 40.0, 0.0});  // |l| = 1.3: stretched
    System stretched = b.build();
    JacobiansAndDifferences j = jacobiansAt(stretched, stretched.state(), 0.0);
    CHECK((j.k - j.kFd).norm() < 1e-5 * j.k.norm());

    SystemBuilder b2;
    const int a2 = b2.addParticle(particleAt(0.0, 0.0)), c2 = b2.addParticle(particleAt(0.6, 0.25));
    b2.addParticle(particleAt(1.5, 1.0));
    b2.emplaceForce<DampedSpringForce>().add({Endpoint::ofParticle(a2), Endpoint::ofParticle(c2), 1.0, 40.0, 0.0});
    System compressed = b2.build();  // |l| = 0.65 < 1
    j = jacobiansAt(compressed, compressed.state(), 0.0);
    // Along the spring, exact; across it the true stiffness is positive (buckling), clamped to 0.
    const Vec2 u = Vec2(0.6, 0.25).normalized(), across(-u.y(), u.x());
    const Eigen::Matrix2d kaa = j.k.block<2, 2>(0, 0), kaaFd = j.kFd.block<2, 2>(0, 0);
    CHECK(u.dot(kaa * u) == doctest::Approx(u.dot(kaaFd * u)).epsilon(1e-6));
    CHECK(across.dot(kaaFd * across) > 1.0);
    CHECK(std::abs(across.dot(kaa * across)) < 1e-12);
    CHECK(largestEigenvalue(j.k) <= 1e-12);
    (void)e;
  }
  SUBCASE("penalty contacts: half-plane exact, disk along its normal") {
    SystemBuilder b;
    b.addParticle(particleAt(0.3, -0.05));  // 5 cm into the ground
    b.addParticle(particleAt(2.0, 0.9));    // inside the disk below
    b.addCollider(std::make_unique<HalfPlaneCollider>(Vec2(0, 1), 0.0, PenaltyParams{2e4, 3.0}));
    b.addCollider(std::make_unique<DiskCollider>(Vec2(2.0, 0.4), 0.6, PenaltyParams{1e4, 0.0}));
    System sys = b.build();
    const JacobiansAndDifferences j = jacobiansAt(sys, sys.state(), 0.0);
    CHECK((j.k.block<2, 2>(0, 0) - j.kFd.block<2, 2>(0, 0)).norm() < 1e-4 * j.k.norm());
    CHECK((j.d - j.dFd).norm() < 1e-6);
    const Vec2 n(0, 1);  // the disk's normal at (2.0, 0.9)
    CHECK(n.dot(j.k.block<2, 2>(2, 2) * n) == doctest::Approx(n.dot(j.kFd.block<2, 2>(2, 2) * n)).epsilon(1e-5));
    CHECK(n.dot(j.k.block<2, 2>(2, 2) * n) < 0.0);
  }
}
