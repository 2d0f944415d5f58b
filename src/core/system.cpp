#include "core/system.hpp"

#include "core/forces/mouse_spring_force.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include "core/pointwise_pass.hpp"
#include "core/rigid_body.hpp"

namespace particles {

void System::setThreads(int threads) {
  if (threads <= 1) {
    pool_.reset();
  } else if (!pool_ || pool_->threads() != threads) {
    pool_.reset();  // its threads end before the new ones start
    pool_ = std::make_unique<WorkerPool>(threads);
  }
  constraintSolver_.setPool(pool_.get());
  projectionSolver_.setPool(pool_.get());
}

void System::derivEval(const Eigen::VectorXd& y, double t, Eigen::VectorXd& dydt, ConstraintForces constraintForces) {
  const StateLayout& layout = model_.layout;
  const StateView s(layout, y);
  const int points = layout.numPoints();
  const Eigen::Index p2 = 2 * Eigen::Index(points);
  const int b = layout.numBodies;
  dydt.resize(layout.size());
  WorkerPool* pool = pool_.get();
  double* force = acc_.force.data();
  const double* velocity = y.data() + layout.velocityOffset();
  const double* invMass = model_.invMass.data();
  // 5. d/dt [x, v] = [v, F/m] for points [begin, end).
  double* derivative = dydt.data();
  auto pointDerivative = [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      derivative[2 * i] = velocity[2 * i];
      derivative[2 * i + 1] = velocity[2 * i + 1];
      derivative[p2 + 2 * i] = force[2 * i] * invMass[i];
      derivative[p2 + 2 * i + 1] = force[2 * i + 1] * invMass[i];
    }
  };
  const bool solveConstraints = constraintForces == ConstraintForces::solve && !constraints_.empty();
  const bool lastStageIsForces = colliders_.empty() && !solveConstraints;

  // 1–2. clear the accumulators and apply the force objects, in order. A run of forces that act
  // point by point is one pass over chunks of points (each force's additions for a point in the
  // force order, as a loop over the forces would make them); the pass that clears, and stage 5
  // when nothing comes between, join it.
  acc_.torque.setZero();
  bool cleared = false;
  bool derived = false;
  for (size_t first = 0; first < forces_.size();) {
    if (!forces_[first]->actsPointwise()) {
      if (!cleared)
        forChunks(pool, size_t(p2), kPointChunk * 2, [&](size_t i, size_t e) { std::fill(force + i, force + e, 0.0); });
      cleared = true;
      forces_[first++]->apply(model_, s, t, acc_);
      continue;
    }
    size_t last = first;
    while (last < forces_.size() && forces_[last]->actsPointwise()) forces_[last++]->preparePoints(model_, s, t, pool);
    const bool clear = !cleared;
    const bool derive = last == forces_.size() && lastStageIsForces;
    if (pointwiseRun_.collect(std::span(forces_).subspan(first, last - first))) {
      const PointwiseRun::Points arrays{force, velocity, model_.mass.data(), invMass, derive ? derivative : nullptr,
                                        p2};
      forChunks(pool, size_t(points), kPointChunk,
                [&](size_t begin, size_t end) { pointwiseRun_.run(arrays, int(begin), int(end), clear); });
    } else {
      forChunks(pool, size_t(points), kPointChunk, [&](size_t chunkBegin, size_t chunkEnd) {
        const int begin = int(chunkBegin), end = int(chunkEnd);
        if (clear) std::fill(force + 2 * begin, force + 2 * end, 0.0);
        for (size_t k = first; k < last; ++k) forces_[k]->applyToPoints(model_, s, t, force, begin, end);
        if (derive) pointDerivative(begin, end);
      });
    }
    cleared = true;
    derived = derive;
    first = last;
  }
  if (!cleared) acc_.force.setZero();
  // 3. collisions: before constraints, which must see every other force
  applyCollisions(model_, s, colliders_, acc_, pool);
  // 4. constraint forces Q̂ = Jᵀλ
  if (constraintForces == ConstraintForces::solve) lastSolve_ = constraintSolver_.solve(model_, s, constraints_, acc_);
  // 5. d/dt [x, v, θ, ω] = [v, F/m, ω, τ/I]
  if (!derived)
    forChunks(pool, size_t(points), kPointChunk,
              [&](size_t begin, size_t end) { pointDerivative(int(begin), int(end)); });
  dydt.segment(layout.angleOffset(), b) = y.segment(layout.omegaOffset(), b);
  dydt.segment(layout.omegaOffset(), b) = acc_.torque.cwiseProduct(model_.invInertia);
}

void System::forceJacobians(const Eigen::VectorXd& y, double t, ForceJacobians& out) const {
  const StateView s(model_.layout, y);
  out.clear();
  out.pool = pool_.get();
  for (const auto& force : forces_) force->addJacobians(model_, s, t, out);
  addCollisionJacobians(model_, s, colliders_, out);
}

// The particles' part of the kinetic energy over points [begin, end): one chunk of kineticEnergy's
// sum, and of checkState's, which must give the same bits.
static double pointsKineticEnergy(const Model& model, const StateView& s, size_t begin, size_t end) {
  double part = 0.0;
  for (size_t i = begin; i < end; ++i) {
    if (model.invMass[i] != 0.0) part += 0.5 * model.mass[i] * s.vel(int(i)).squaredNorm();
  }
  return part;
}

double System::bodiesKineticEnergy(const Eigen::VectorXd& y) const {
  const StateView s(model_.layout, y);
  double k = 0.0;
  for (int j = 0; j < model_.layout.numBodies; ++j) {
    k += 0.5 * model_.bodies[size_t(j)].inertia * s.omega(j) * s.omega(j);
  }
  return k;
}

double System::kineticEnergy(const Eigen::VectorXd& y) const {
  const StateView s(model_.layout, y);
  // Summed in fixed chunks of points, added in chunk order (sumChunks): the same bits on any
  // thread count.
  std::vector<double> partials;
  const double k = sumChunks(pool_.get(), size_t(model_.layout.numPoints()), kPointChunk, partials,
                             [&](size_t begin, size_t end) { return pointsKineticEnergy(model_, s, begin, end); });
  return k + bodiesKineticEnergy(y);
}

System::StateCheck System::checkState(const Eigen::VectorXd& y, StateCheckScratch& scratch) const {
  const StateView s(model_.layout, y);
  const size_t points = size_t(model_.layout.numPoints());
  const double* position = y.data();
  const double* velocity = y.data() + model_.layout.velocityOffset();
  scratch.nonFinite.assign(chunkCount(points, kPointChunk), 0);
  // kineticEnergy's chunks and sum, with each chunk's positions and velocities tested on the way:
  // 0·x is 0 for a finite x and NaN for ±∞ or NaN, one multiply and compare an entry that
  // vectorises (Eigen's allFinite forms x − x twice), into a local flag (no early exit).
  const double k = sumChunks(pool_.get(), points, kPointChunk, scratch.partials, [&](size_t begin, size_t end) {
    bool bad = false;
    for (size_t i = 2 * begin; i < 2 * end; ++i) {
      bad |= std::isnan(position[i] * 0.0);
      bad |= std::isnan(velocity[i] * 0.0);
    }
    scratch.nonFinite[begin / kPointChunk] = bad ? 1 : 0;
    return pointsKineticEnergy(model_, s, begin, end);
  });
  bool finite = std::find(scratch.nonFinite.begin(), scratch.nonFinite.end(), 1) == scratch.nonFinite.end();
  const Eigen::Index bodies = model_.layout.numBodies;
  for (Eigen::Index j = 0; j < bodies; ++j) {
    finite &= std::isfinite(y[model_.layout.angleOffset() + j]) && std::isfinite(y[model_.layout.omegaOffset() + j]);
  }
  return {finite, k + bodiesKineticEnergy(y)};
}

EnergyReport System::energy(const Eigen::VectorXd& y, double t) const {
  const StateView s(model_.layout, y);
  EnergyReport report;
  report.kinetic = kineticEnergy(y);
  auto add = [&](std::string_view kind, double u) {
    auto it = std::find_if(report.potentialBySource.begin(), report.potentialBySource.end(),
                           [&](const EnergySource& e) { return e.kind == kind; });
    if (it == report.potentialBySource.end()) {
      report.potentialBySource.push_back({std::string(kind), u});
    } else {
      it->energy += u;
    }
    report.potential += u;
  };
  for (const auto& force : forces_) {
    if (!force->isDissipative()) add(force->kind(), force->potentialEnergy(model_, s, t));
  }
  if (!colliders_.empty()) add("collision", collisionPotential(model_, s, colliders_));
  return report;
}

std::vector<MouseSpringForce*> System::mice() {
  std::vector<MouseSpringForce*> out;
  for (const auto& force : forces_) {
    if (auto* mouse = dynamic_cast<MouseSpringForce*>(force.get())) out.push_back(mouse);
  }
  return out;
}

Drawing System::draw() const {
  Drawing d;
  draw(d);
  return d;
}

void System::draw(Drawing& d, SpringDetail springs, const DrawDetail& detail) const {
  const StateView s = view();
  const StateLayout& layout = model_.layout;
  d.clear();
  d.time = t_;
  // The long lists on the system's threads (a million-particle frame's drawing is 100 MB).
  d.particles.resize(size_t(layout.numParticles));
  d.particleFixed.resize(size_t(layout.numParticles));
  forChunks(pool_.get(), size_t(layout.numParticles), kPointChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      d.particles[i] = s.pos(int(i));
      d.particleFixed[i] = model_.isFixed(int(i)) ? 1 : 0;
    }
  });
  for (int j = 0; j < layout.numBodies; ++j) {
    d.bodies.push_back({s.pos(layout.bodyPoint(j)), s.angle(j), model_.bodies[size_t(j)].size});
  }
  if (springs == SpringDetail::topology) {
    std::call_once(springTopology_->made, [&] {
      auto topology = std::make_shared<Drawing::SpringTopology>();
      bool byIndex = true;
      for (const auto& force : forces_) byIndex = byIndex && force->addSpringTopology(*topology);
      if (byIndex) springTopology_->topology = std::move(topology);
    });
    d.springTopology = springTopology_->topology;
  }
  for (const auto& force : forces_) {
    // Forces by index add no springs: their ends' positions are the particles'.
    if (d.springTopology && force->isSpringSet()) continue;
    force->draw(s, t_, d, pool_.get());
  }
  for (const auto& constraint : constraints_) constraint->draw(s, d);
  for (const auto& collider : colliders_) collider->draw(d);
  if (detail.velocities || detail.masses) drawDetail(d, detail);
}

void System::drawDetail(Drawing& d, const DrawDetail& detail) const {
  const StateView s = view();
  const StateLayout& layout = model_.layout;
  const size_t n = size_t(layout.numParticles);
  if (detail.velocities) {
    d.particleVelocities.resize(n);
    forChunks(pool_.get(), n, kPointChunk, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) d.particleVelocities[i] = s.vel(int(i));
    });
    for (int j = 0; j < layout.numBodies; ++j) {
      d.bodyVelocities.push_back(s.vel(layout.bodyPoint(j)));
      d.bodyAngularVelocities.push_back(s.omega(j));
    }
  }
  if (detail.masses) {
    d.particleMasses.assign(model_.mass.data(), model_.mass.data() + n);
    d.bodyMasses.assign(model_.mass.data() + n, model_.mass.data() + n + size_t(layout.numBodies));
  }
}

void System::restore(const Checkpoint& c) {
  if (c.y.size() != y_.size()) throw std::invalid_argument("a checkpoint of another system");
  y_ = c.y;
  t_ = c.t;
  constraintSolver_.restoreWarmStart(c.warmStart);
  lastSolve_ = c.lastSolve;
}

void System::addAccelerations(Drawing& d) {
  const StateLayout& layout = model_.layout;
  Eigen::VectorXd warmStart = constraintSolver_.warmStart();
  const ConstraintSolveStats lastSolve = lastSolve_;
  Eigen::VectorXd dydt;
  derivEval(y_, t_, dydt);
  constraintSolver_.restoreWarmStart(std::move(warmStart));
  lastSolve_ = lastSolve;
  const Eigen::Index accelerations = layout.velocityOffset();  // dydt = [v, a, ω, α]: a after v
  const size_t n = size_t(layout.numParticles);
  d.particleAccelerations.resize(n);
  for (size_t i = 0; i < n; ++i) {
    d.particleAccelerations[i] = {dydt[accelerations + 2 * Eigen::Index(i)], dydt[accelerations + 2 * Eigen::Index(i) + 1]};
  }
  d.bodyAccelerations.clear();
  for (int j = 0; j < layout.numBodies; ++j) {
    const Eigen::Index at = accelerations + 2 * Eigen::Index(layout.bodyPoint(j));
    d.bodyAccelerations.push_back({dydt[at], dydt[at + 1]});
  }
}

double System::constraintError(const Eigen::VectorXd& y) const {
  const StateView s(model_.layout, y);
  double worst = 0.0;
  for (const auto& c : constraints_) worst = std::max(worst, c->violation(s));
  return worst;
}

double System::penetration(const Eigen::VectorXd& y) const {
  return maxPenetration(model_, StateView(model_.layout, y), colliders_);
}

int SystemBuilder::addParticle(const ParticleSpec& spec) {
  particles_.push_back(spec);
  return int(particles_.size()) - 1;
}

int SystemBuilder::addRigidBody(const RigidBodySpec& spec) {
  bodies_.push_back(spec);
  return int(bodies_.size()) - 1;
}

Force& SystemBuilder::addForce(std::unique_ptr<Force> force) { return *forces_.emplace_back(std::move(force)); }

Constraint& SystemBuilder::addConstraint(std::unique_ptr<Constraint> constraint) {
  return *constraints_.emplace_back(std::move(constraint));
}

Collider& SystemBuilder::addCollider(std::unique_ptr<Collider> collider) {
  return *colliders_.emplace_back(std::move(collider));
}

System SystemBuilder::build() {
  System sys;
  Model& m = sys.model_;
  m.layout = {int(particles_.size()), int(bodies_.size())};
  const StateLayout& layout = m.layout;
  const int n = layout.numParticles;
  m.mass.resize(layout.numPoints());
  m.invMass.resize(layout.numPoints());
  m.invInertia.resize(layout.numBodies);
  sys.y_.setZero(layout.size());
  double* y = sys.y_.data();
  const Eigen::Index v = layout.velocityOffset();

  for (int i = 0; i < n; ++i) {
    const ParticleSpec& p = particles_[size_t(i)];
    if (!(p.mass > 0.0)) throw std::invalid_argument("particle " + std::to_string(i) + ": mass must be > 0");
    m.mass[i] = p.mass;
    m.invMass[i] = p.fixed ? 0.0 : 1.0 / p.mass;
    y[2 * i] = p.pos.x();
    y[2 * i + 1] = p.pos.y();
    // A fixed particle never moves, whatever velocity it was given.
    y[v + 2 * i] = p.fixed ? 0.0 : p.vel.x();
    y[v + 2 * i + 1] = p.fixed ? 0.0 : p.vel.y();
    m.particleNames.push_back(p.name);
  }
  for (int j = 0; j < layout.numBodies; ++j) {
    const RigidBodySpec& b = bodies_[size_t(j)];
    if (!(b.mass > 0.0) || !(b.size.x() > 0.0) || !(b.size.y() > 0.0)) {
      throw std::invalid_argument("rigid body " + std::to_string(j) + ": mass and size must be > 0");
    }
    const int point = layout.bodyPoint(j);
    m.mass[point] = b.mass;
    m.invMass[point] = 1.0 / b.mass;
    m.bodies.push_back({b.size, rectangleInertia(b.mass, b.size)});
    m.invInertia[j] = 1.0 / m.bodies.back().inertia;
    y[2 * point] = b.pos.x();
    y[2 * point + 1] = b.pos.y();
    y[v + 2 * point] = b.vel.x();
    y[v + 2 * point + 1] = b.vel.y();
    sys.y_[layout.angleOffset() + j] = b.angle;
    sys.y_[layout.omegaOffset() + j] = b.omega;
    m.bodyNames.push_back(b.name);
  }

  for (const auto& force : forces_) force->validate(layout);
  for (const auto& c : constraints_) {
    for (int p : c->particles()) {
      if (p < 0 || p >= n) {
        throw std::invalid_argument(std::string(c->kind()) + " constraint: particle " + std::to_string(p) +
                                    " does not exist");
      }
    }
  }

  sys.forces_ = std::move(forces_);
  sys.constraints_ = std::move(constraints_);
  sys.colliders_ = std::move(colliders_);
  sys.constraintSolver_ = ConstraintSolver(solverOptions_);
  sys.projectionSolver_ = ConstraintSolver(solverOptions_);
  sys.acc_.resize(layout);

  const StateView s(layout, sys.y_);
  double scale = sys.kineticEnergy(sys.y_);
  for (const auto& force : sys.forces_) scale += std::abs(force->energyScale(m, s));
  // Floor: 1 J per kg of mass, so a system at rest with no forces still has a yardstick.
  scale += m.mass.sum() * 1.0;
  sys.energyScale_ = scale;

  particles_.clear();
  bodies_.clear();
  shared_.clear();
  return sys;
}

}  // namespace particles
