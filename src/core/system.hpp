#pragma once
// The system (docs/physics.md §1–2): a model, the current state vector and time, and the force objects,
// constraints and colliders that act on it. derivEval is the one interface the integrators use.
//
// Built with SystemBuilder, so that the layout of the state vector is fixed before stepping.

#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/collisions.hpp"
#include "core/constraint_solver.hpp"
#include "core/force.hpp"
#include "core/implicit_solver.hpp"
#include "core/model.hpp"
#include "core/pointwise_pass.hpp"
#include "core/worker_pool.hpp"

namespace particles {

class MouseSpringForce;

struct ParticleSpec {
  Vec2 pos = Vec2::Zero();
  Vec2 vel = Vec2::Zero();
  double mass = 1.0;   // kg, > 0 (a fixed particle keeps its mass for gravity's bookkeeping)
  bool fixed = false;  // fixed: inverse mass 0, never moves
  std::string name;
};

struct RigidBodySpec {
  Vec2 pos = Vec2::Zero();  // centre of mass
  Vec2 vel = Vec2::Zero();
  double angle = 0.0;  // rad, counter-clockwise
  double omega = 0.0;  // rad/s
  Vec2 size = Vec2(1.0, 1.0);  // width, height, m
  double mass = 1.0;
  std::string name;
};

struct EnergySource {
  std::string kind;  // "gravity", "spring", "mouse", "collision", …
  double energy;     // J
};

struct EnergyReport {
  double kinetic = 0.0;    // Σ ½ m v² + ½ I ω²
  double potential = 0.0;  // Σ over sources
  std::vector<EnergySource> potentialBySource;  // one entry per kind, in order of first appearance
  double total() const { return kinetic + potential; }
};

class System {
 public:
  const Model& model() const { return model_; }
  const StateLayout& layout() const { return model_.layout; }

  Eigen::VectorXd& state() { return y_; }
  const Eigen::VectorXd& state() const { return y_; }
  StateView view() const { return StateView(model_.layout, y_); }
  double time() const { return t_; }
  void setTime(double t) { t_ = t; }

  // dy/dt at (y, t): clear accumulators, apply forces, collisions, constraints, then write
  // [v, F/m, ω, τ/I] (docs/physics.md §2). Not const: it reuses scratch space and warm-starts λ.
  // Without constraint forces for the integrators that keep constraints by projection instead.
  enum class ConstraintForces { solve, skip };
  void derivEval(const Eigen::VectorXd& y, double t, Eigen::VectorXd& dydt,
                 ConstraintForces constraintForces = ConstraintForces::solve);

  // ∂f/∂x and ∂f/∂v at (y, t) of every force and collider that linearises itself (the implicit
  // integrator's matrix, core/force_jacobians.hpp); constraint forces are not included.
  void forceJacobians(const Eigen::VectorXd& y, double t, ForceJacobians& out) const;
  // Moves y onto the constraints (positions, then velocities: ConstraintSolver::project); for the
  // integrators whose steps do not keep them by themselves.
  void projectOntoConstraints(Eigen::VectorXd& y) { projectionSolver_.project(model_, y, constraints_); }
  // Only the velocities, with J at y's positions as they are (Ċ = 0).
  void projectVelocitiesOntoConstraints(Eigen::VectorXd& y) {
    projectionSolver_.projectVelocities(model_, y, constraints_);
  }

  // The threads derivEval, the integrators and the solvers share (core/worker_pool.hpp); 1 (the
  // default) starts none. Results are the same bits for every count.
  void setThreads(int threads);
  int threads() const { return pool_ ? pool_->threads() : 1; }
  // Whether a derivative evaluation has work for more than one thread: more points than one chunk
  // of its passes holds (core/worker_pool.hpp). The 25² cloth does not; the 100² does.
  bool spreadsOverThreads() const { return size_t(model_.layout.numPoints()) > kPointChunk; }
  WorkerPool* pool() { return pool_.get(); }
  // The implicit integrators' linear solve (core/implicit_solver.hpp); automatic by default.
  void setImplicitSolver(ImplicitSolver solver) { implicitSolver_ = solver; }
  ImplicitSolver implicitSolver() const { return implicitSolver_; }

  double kineticEnergy(const Eigen::VectorXd& y) const;
  // The explosion guard's look at a state after each step, in one pass over it on the threads:
  // whether every entry is finite, and kineticEnergy(y) (the same bits) when it is.
  struct StateCheck {
    bool finite;
    double kinetic;
  };
  struct StateCheckScratch {  // kept by the caller, so that the pass does not allocate
    std::vector<double> partials;
    std::vector<char> nonFinite;
  };
  StateCheck checkState(const Eigen::VectorXd& y, StateCheckScratch& scratch) const;
  EnergyReport energy(const Eigen::VectorXd& y, double t) const;
  EnergyReport energy() const { return energy(y_, t_); }
  // The current state as plain geometry for drawing: particles, bodies, and what every force,
  // constraint and collider shows of itself (core/drawing.hpp). The long lists are filled on the
  // system's threads: the same drawing for every count.
  Drawing draw() const;
  // The same into `out`, reusing its lists' storage: a render's frames draw into one Drawing, so
  // that a large scene's lists are not allocated (and their pages not faulted in) every frame.
  // With SpringDetail::topology, springs that all join particles come as Drawing::springTopology
  // (built on the first such call, then shared by every drawing) instead of in Drawing::springs.
  // With `detail`, also what a style colours by: velocities and masses. Accelerations are
  // addAccelerations' (they need an evaluation of the forces, which is not const).
  void draw(Drawing& out, SpringDetail springs = SpringDetail::positions, const DrawDetail& detail = {}) const;
  // Fills out.particleAccelerations and out.bodyAccelerations with dv/dt at the current state: every
  // force, collision and constraint force over the mass (docs/physics.md §2). One evaluation of the
  // derivative, after which the constraint solver's warm start and the last solve's statistics are
  // put back, so that a styled render steps the same bits as a plain one.
  void addAccelerations(Drawing& out);

  // Everything that carries from one step to the next inside the System (the state, the time and
  // the constraint solver's warm start; the rest is scratch): a render that looks at every frame
  // once before drawing any (style/quantity.hpp's auto ranges, a camera that fits the whole run)
  // steps from a checkpoint, then restores it and steps again, the same bits as the first time.
  struct Checkpoint {
    Eigen::VectorXd y;
    double t = 0.0;
    Eigen::VectorXd warmStart;
    ConstraintSolveStats lastSolve;
  };
  Checkpoint checkpoint() const { return {y_, t_, constraintSolver_.warmStart(), lastSolve_}; }
  void restore(const Checkpoint& c);

  double constraintError(const Eigen::VectorXd& y) const;  // largest violation, m
  double penetration(const Eigen::VectorXd& y) const;      // largest collider depth, m
  // Energy the initial system can plausibly hold (kinetic plus each force's scale), J; the
  // explosion guard compares kinetic energy against a multiple of it.
  double energyScale() const { return energyScale_; }
  const ConstraintSolveStats& lastConstraintSolve() const { return lastSolve_; }

  const std::vector<std::unique_ptr<Force>>& forces() const { return forces_; }
  // The scripted mice (the `mouse` section's, in order), for a program that moves them.
  std::vector<MouseSpringForce*> mice();
  const ConstraintList& constraints() const { return constraints_; }
  const ColliderList& colliders() const { return colliders_; }

 private:
  friend class SystemBuilder;
  void drawDetail(Drawing& out, const DrawDetail& detail) const;  // draw's velocities and masses
  System() = default;

  double bodiesKineticEnergy(const Eigen::VectorXd& y) const;

  Model model_;
  Eigen::VectorXd y_;
  double t_ = 0.0;
  std::vector<std::unique_ptr<Force>> forces_;
  ConstraintList constraints_;
  ColliderList colliders_;
  ConstraintSolver constraintSolver_;
  ConstraintSolver projectionSolver_;  // its own, so the multipliers' warm start stays untouched
  ForceAccumulator acc_;
  PointwiseRun pointwiseRun_;  // derivEval's scratch: the terms of the current run of pointwise forces
  ConstraintSolveStats lastSolve_;
  std::unique_ptr<WorkerPool> pool_;  // null: one thread
  ImplicitSolver implicitSolver_ = ImplicitSolver::automatic;
  double energyScale_ = 0.0;
  // The springs by index, made once on the first draw that asks (by whichever thread draws first:
  // two renderers may draw one system), null when a spring has an end on a body.
  struct SpringTopologyCache {
    std::once_flag made;
    std::shared_ptr<const Drawing::SpringTopology> topology;
  };
  std::unique_ptr<SpringTopologyCache> springTopology_ = std::make_unique<SpringTopologyCache>();
};

class SystemBuilder {
 public:
  int addParticle(const ParticleSpec& spec);  // returns the particle index
  int addRigidBody(const RigidBodySpec& spec);  // returns the body index
  Force& addForce(std::unique_ptr<Force> force);
  Constraint& addConstraint(std::unique_ptr<Constraint> constraint);
  Collider& addCollider(std::unique_ptr<Collider> collider);
  template <typename T, typename... Args>
  T& emplaceForce(Args&&... args) {
    return static_cast<T&>(addForce(std::make_unique<T>(std::forward<Args>(args)...)));
  }
  // The one force object of type T kept under `slot`, made on first use (and placed in the force
  // order there): every explicit spring of a scenario goes into one DampedSpringForce, whose flat
  // arrays are the spring loop's fast path.
  template <typename T>
  T& sharedForce(std::string_view slot) {
    for (auto& [name, force] : shared_) {
      if (name == slot) return static_cast<T&>(*force);
    }
    T& made = emplaceForce<T>();
    shared_.emplace_back(std::string(slot), &made);
    return made;
  }
  void setConstraintSolverOptions(const ConstraintSolverOptions& options) { solverOptions_ = options; }

  int numParticles() const { return int(particles_.size()); }
  int numBodies() const { return int(bodies_.size()); }

  // Lays out the state vector and hands everything over. Throws std::invalid_argument when a
  // mass or size is not positive or an index is out of range (the scenario loader reports such
  // errors with file and line before it gets here).
  System build();

 private:
  std::vector<ParticleSpec> particles_;
  std::vector<RigidBodySpec> bodies_;
  std::vector<std::unique_ptr<Force>> forces_;
  ConstraintList constraints_;
  ColliderList colliders_;
  ConstraintSolverOptions solverOptions_;
  std::vector<std::pair<std::string, Force*>> shared_;
};

}  // namespace particles
