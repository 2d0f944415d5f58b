// Results do not depend on the thread count (src/core/worker_pool.hpp, docs/architecture.md,
// "Threads"): the state vector, and what the program reports from it, are the same bits on 1, 2, 3,
// 4 and 8 threads. The three demos and the stiff cloth through their scripted drags, and the 100²
// and 316² cloths (several chunks per pass: 19,800 and 199,080 springs) with every integrator,
// since each integrator reaches the threads through its own code. Also run under ThreadSanitizer
// (scripts/test's TSan stage, particles_core_tests) and AddressSanitizer (build-asan).
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/constraints/rod_constraint.hpp"
#include "core/forces/gravity_force.hpp"
#include "core/solver.hpp"
#include "sanitizer.hpp"
#include "scenario/runner.hpp"
#include "scenario/scenario.hpp"
#include "source_tree.hpp"

using namespace particles;
using namespace particles::scenario;
using particles::test::kUnderSanitizer;

using particles::test::kScenarios;

namespace {


// Each compared against one thread. 3 leaves a thread with more chunks than the others; 8 is more
// threads than the 100² cloth has chunks (3 per pass), so some of them join a job late and find
// none left. Under the sanitizers (TSan 5–20 times slower; ASan's -O1 with Eigen's assertions,
// build-asan, 30 times on backward Euler) fewer, since a data race needs two threads, not a
// particular number of them: under TSan 3 and 8 on the large cloths, 3 alone on the demos (whose
// passes are one chunk each today: the 25² stiff cloth took 31 s under ASan with 3 and 8); under
// ASan, which looks for bad memory, not races, 3 alone everywhere (the net of rods: 81 s with 3 and 8).
constexpr int kAllThreadCounts[] = {2, 3, 4, 8};
constexpr int kSanitizerThreadCounts[] = {3, 8};
constexpr int kThreeThreads[] = {3};
const std::span<const int> kThreadCounts =
    particles::test::kUnderAddressSanitizer ? std::span<const int>(kThreeThreads)
    : kUnderSanitizer                       ? std::span<const int>(kSanitizerThreadCounts)
                                            : std::span<const int>(kAllThreadCounts);
const std::span<const int> kDemoThreadCounts =
    kUnderSanitizer ? std::span<const int>(kThreeThreads) : std::span<const int>(kAllThreadCounts);

// What a run has produced at one time: everything a later step, a --trace or a --stats row reads.
struct Snapshot {
  long steps = 0;
  double time = 0.0;
  Eigen::VectorXd state;
  Sample sample;                     // energies, constraint error, penetration (--stats)
  ConstraintSolveStats constraints;  // the last derivEval's multiplier solve
  int cgIterations = 0;              // backward Euler's last solve (the Solver's runs only)
};

Snapshot snapshotOf(const System& system, long steps, int cgIterations) {
  return {steps, system.time(), system.state(), sampleOf(system), system.lastConstraintSolve(), cgIterations};
}

// Where entry `index` of the state vector belongs, for messages: "vy of cloth[3][4]".
std::string describeEntry(const Model& model, Eigen::Index index) {
  const StateLayout& layout = model.layout;
  if (index < layout.angleOffset()) {
    const bool velocity = index >= layout.velocityOffset();
    const Eigen::Index within = velocity ? index - layout.velocityOffset() : index;
    return fmt::format("{}{} of {}", velocity ? "v" : "", within % 2 == 0 ? "x" : "y",
                       pointName(model, int(within / 2)));
  }
  const bool omega = index >= layout.omegaOffset();
  const int body = int(index - (omega ? layout.omegaOffset() : layout.angleOffset()));
  return fmt::format("{} of {}", omega ? "omega" : "angle", pointName(model, layout.bodyPoint(body)));
}

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// The first entry where two vectors' bits differ (sizes first), or nothing when they are the same bytes.
std::optional<Eigen::Index> firstDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return 0;
  if (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * size_t(a.size())) == 0) return std::nullopt;
  for (Eigen::Index i = 0;; ++i) {
    if (!sameBits(a[i], b[i])) return i;
  }
}

// Checks that `threaded` is the same bits as `serial`; a difference names the first entry that
// differs, with both values in hexadecimal (every bit shown).
void checkSameBits(const Model& model, const std::vector<Snapshot>& serial, const std::vector<Snapshot>& threaded,
                   int threads) {
  CAPTURE(threads);
  REQUIRE(serial.size() == threaded.size());
  for (size_t k = 0; k < serial.size(); ++k) {
    const Snapshot& a = serial[k];
    const Snapshot& b = threaded[k];
    CAPTURE(a.steps);
    CAPTURE(a.time);
    CHECK(a.steps == b.steps);
    CHECK(sameBits(a.time, b.time));
    REQUIRE(a.state.size() == b.state.size());
    if (const auto i = firstDifference(a.state, b.state)) {
      FAIL_CHECK(fmt::format("state[{}] ({}) differs: {:a} on 1 thread, {:a} on {}", *i, describeEntry(model, *i),
                             a.state[*i], b.state[*i], threads));
    }
    CHECK(sameBits(a.sample.kinetic, b.sample.kinetic));
    CHECK(sameBits(a.sample.potential, b.sample.potential));
    CHECK(sameBits(a.sample.constraintError, b.sample.constraintError));
    CHECK(sameBits(a.sample.penetration, b.sample.penetration));
    CHECK(a.constraints.rows == b.constraints.rows);
    CHECK(a.constraints.iterations == b.constraints.iterations);
    CHECK(sameBits(a.constraints.relativeResidual, b.constraints.relativeResidual));
    CHECK(a.cgIterations == b.cgIterations);
  }
}

Scenario load(const std::string& name, const std::vector<Override>& overrides) {
  return loadScenarioFile(kScenarios / (name + ".yaml"), overrides);
}

// A demo as `particles run` steps it (the Stepper, the scenario's integrator and dt), snapshots
// at the given times.
std::vector<Snapshot> stepDemo(Scenario& s, int threads, const std::vector<double>& times) {
  s.system.setThreads(threads);
  REQUIRE(s.system.threads() == threads);
  Stepper stepper(s.system, s.simulation.integrator, s.simulation.dt);
  std::vector<Snapshot> out{snapshotOf(s.system, 0, 0)};
  for (double t : times) {
    stepper.advanceTo(t);
    out.push_back(snapshotOf(s.system, stepper.steps(), 0));
  }
  return out;
}

void checkDemo(const std::string& name, const std::vector<double>& times) {
  CAPTURE(name);
  Scenario serial = load(name, {});
  const std::vector<Snapshot> expected = stepDemo(serial, 1, times);
  REQUIRE(expected.back().steps > 0);
  for (int threads : kDemoThreadCounts) {
    Scenario s = load(name, {});
    checkSameBits(s.system.model(), expected, stepDemo(s, threads, times), threads);
  }
}

// `steps` steps of one integrator through the Solver from time `start` (the cloth's drag starts
// at 1.5 s: from 1.6 s the mouse spring pulls), a snapshot after each.
std::vector<Snapshot> stepCloth(Scenario& s, Integrator integrator, int threads, double start, int steps) {
  s.system.setThreads(threads);
  REQUIRE(s.system.threads() == threads);
  s.system.setTime(start);
  Solver solver(integrator);
  std::vector<Snapshot> out;
  for (int k = 0; k < steps; ++k) {
    solver.doStep(s.system, s.simulation.dt);
    out.push_back(snapshotOf(s.system, solver.steps(), solver.lastImplicitStep().iterations));
  }
  return out;
}

// The demo cloth at side × side particles (the grab, cloth[24][12], is in every grid from 25²).
void checkCloth(int side, Integrator integrator, int steps, std::vector<Override> overrides = {}) {
  CAPTURE(side);
  CAPTURE(integratorName(integrator));
  overrides.push_back({"grids.0.size", fmt::format("[{}, {}]", side, side), "test"});
  constexpr double kStart = 1.6;
  Scenario serial = load("cloth", overrides);
  const std::vector<Snapshot> expected = stepCloth(serial, integrator, 1, kStart, steps);
  CHECK(expected.back().state.allFinite());
  for (int threads : kThreadCounts) {
    Scenario s = load("cloth", overrides);
    checkSameBits(s.system.model(), expected, stepCloth(s, integrator, threads, kStart, steps), threads);
  }
}

// A net of side × side particles 2 cm apart joined by rods to their right and lower neighbours
// (2·side·(side − 1) rows, closing loops, so the constraint solver takes Jacobi CG), the top row
// fixed, under gravity; the bottom row starts 1 cm to the side so that the rods pull from the
// first step.
System rodGrid(int side) {
  SystemBuilder b;
  for (int r = 0; r < side; ++r) {
    for (int c = 0; c < side; ++c) {
      ParticleSpec p;
      p.pos = Vec2(0.02 * c + (r == side - 1 ? 0.01 : 0.0), -0.02 * r);
      p.mass = 0.01;
      p.fixed = r == 0;
      b.addParticle(p);
    }
  }
  for (int r = 0; r < side; ++r) {
    for (int c = 0; c < side; ++c) {
      const int p = r * side + c;
      if (c + 1 < side) b.addConstraint(std::make_unique<RodConstraint>(p, p + 1, 0.02));
      if (r + 1 < side) b.addConstraint(std::make_unique<RodConstraint>(p, p + side, 0.02));
    }
  }
  b.emplaceForce<GravityForce>(Vec2(0, -9.81));
  return b.build();
}

std::vector<Snapshot> stepNet(int side, Integrator integrator, int threads, int steps) {
  System system = rodGrid(side);
  system.setThreads(threads);
  Solver solver(integrator);
  std::vector<Snapshot> out;
  for (int k = 0; k < steps; ++k) {
    solver.doStep(system, 0.002);
    out.push_back(snapshotOf(system, solver.steps(), solver.lastImplicitStep().iterations));
  }
  return out;
}

}  // namespace

TEST_CASE("determinism: the comparison sees a change of one bit anywhere") {
  Scenario s = load("rigid_chain", {});
  const Eigen::VectorXd& y = s.system.state();
  CHECK(!firstDifference(y, y));
  for (Eigen::Index i : {Eigen::Index(0), y.size() / 2, y.size() - 1}) {
    Eigen::VectorXd changed = y;
    changed[i] = std::nextafter(changed[i], 1e300);
    CHECK(firstDifference(y, changed) == i);
  }
  Eigen::VectorXd positiveZero = y, negativeZero = y;
  positiveZero[1] = 0.0;
  negativeZero[1] = -0.0;
  CHECK(firstDifference(positiveZero, negativeZero) == 1);                       // == would call them equal
  CHECK(firstDifference(y, Eigen::VectorXd(y.head(y.size() - 1))).has_value());  // a size apart
  const Model& model = s.system.model();
  CHECK(describeEntry(model, s.system.layout().velocityOffset() + 1) == "vy of " + pointName(model, 0));
  CHECK(describeEntry(model, s.system.layout().omegaOffset()) == "omega of link0");
}

// The demos' scenario settings, through their scripted drags: the cloth's mouse holds from 1.5 s,
// the rigid chain's from 1.2 s, the soft body's from 12 s; the stiff cloth steps by backward Euler.
TEST_CASE("determinism: the cloth demo, 1–8 threads, through the drag") {
  checkDemo("cloth", {0.5, 1.6, 2.0});
}
TEST_CASE("determinism: the soft body demo, 1–8 threads, through the drag") {
  checkDemo("soft_body", {6.0, 12.3, 15.0});
}
TEST_CASE("determinism: the rigid chain demo, 1–8 threads, through the drag") {
  checkDemo("rigid_chain", {0.6, 1.3, 1.6});
}
TEST_CASE("determinism: the stiff cloth (backward Euler), 1–8 threads, through the drag") {
  checkDemo("cloth_stiff", {0.5, 1.6, 2.0});
}

// 100²: 10,000 points (3 chunks of the pointwise passes), 40,000 state entries (3 chunks of the
// vector updates), 19,800 springs. Each integrator's threaded code is its own.
TEST_CASE("determinism: every integrator on the 100² cloth, 1–8 threads") {
  for (Integrator integrator : allIntegrators()) checkCloth(100, integrator, kUnderSanitizer ? 2 : 4);
}

// Collisions on threads: the 100² cloth's lower half inside a half-plane and its middle on a disk
// (3 chunks of particles, each particle's contacts in collider order).
TEST_CASE("determinism: the 100² cloth in contact with a half-plane and a disk, 1–8 threads") {
  const std::vector<Override> colliders{{"colliders",
                                         "[{type: half_plane, normal: [0, 1], offset: 0.2, k: 1, damping: 0.01}, "
                                         "{type: disk, center: [0, 0.5], radius: 0.3, k: 1, damping: 0.01}]",
                                         "test"}};
  std::vector<Override> scene = colliders;
  scene.push_back({"grids.0.size", "[100, 100]", "test"});
  REQUIRE(sampleOf(load("cloth", scene).system).penetration > 0.1);  // in contact from the start
  checkCloth(100, Integrator::rk4, kUnderSanitizer ? 1 : 3, colliders);
  if (!kUnderSanitizer) checkCloth(100, Integrator::backwardEuler, 2, colliders);
}

// 316² (the large cloth of the benchmarks): 25 chunks per pointwise pass. A step of RK4 costs about
// 10 ms there, one of backward Euler about 100 ms and its first (which lays out the matrix) about
// 300 ms (bench/README.md), so few steps: backward Euler's later steps are the 100² cloth's.
// Under ThreadSanitizer loading the scene takes 1 s and backward Euler's first step 11 s: there,
// one step of RK4 (the pointwise passes and vector updates at 25 chunks), the rest at 100².
TEST_CASE("determinism: the 316² cloth, 1–8 threads") {
  checkCloth(316, Integrator::rk4, kUnderSanitizer ? 1 : 2);
  if (kUnderSanitizer) return;
  checkCloth(316, Integrator::symplecticEuler, 2);
  checkCloth(316, Integrator::backwardEuler, 1);
}

// The constraint solver on threads: a 100² net of rods (19,800 rows: 3 chunks of its Jacobi CG's
// products, 2 of its dot products; 10,000 particles' sums of Jᵀλ), by RK4 (the multipliers'
// forces) and symplectic Euler (projection onto the rods).
TEST_CASE("determinism: a net of 19,800 rods, 1–8 threads") {
  const int side = 100;
  for (Integrator integrator : {Integrator::rk4, Integrator::symplecticEuler}) {
    CAPTURE(integratorName(integrator));
    const int steps = kUnderSanitizer ? 1 : 3;
    const std::vector<Snapshot> expected = stepNet(side, integrator, 1, steps);
    REQUIRE(expected.back().state.allFinite());
    if (integrator == Integrator::rk4) CHECK(expected.back().constraints.iterations > 1);
    const System model = rodGrid(side);
    // Under either sanitizer 3 threads alone (47 s under TSan with 3 and 8): the cloths above reach
    // the threads that join late and find no chunk left.
    for (int threads : kUnderSanitizer ? std::span<const int>(kThreeThreads) : kThreadCounts)
      checkSameBits(model.model(), expected, stepNet(side, integrator, threads, steps), threads);
  }
}
