// The spring loop's two versions (core/forces/spring_force_kernel.hpp) and the fused pass over the
// points (core/pointwise_pass.hpp) against the plain code they stand for, bit for bit: whichever
// runs, a simulation's numbers must not change (DEVELOPERS.md: same binary, same scenario, same
// bits), and the AVX2 loop runs on some machines and not on others.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/forces/damped_spring_force.hpp"
#include "core/forces/drag_force.hpp"
#include "core/forces/gravity_force.hpp"
#include "core/forces/spring_force_kernel.hpp"
#include "core/grid.hpp"
#include "skip.hpp"
#include "support.hpp"

using namespace particles;
using namespace particles::test;

namespace {

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// Random springs between 64 particles, with the awkward cases among them: both ends at one place
// (|l| = 0), |l| just above and below the 1e-12 m cut-off, huge and tiny lengths and stiffnesses,
// zero rest length, zero damping, and one end at NaN.
struct RandomSprings {
  std::vector<int> endA, endB;
  std::vector<double> rest, ks, kd, x, v;

  explicit RandomSprings(size_t n) {
    std::mt19937_64 random(20261126);  // fixed: the test sees the same springs every run
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const int particles = 64;
    for (int p = 0; p < particles; ++p) {
      const double scale = std::pow(10.0, 6.0 * unit(random));
      x.push_back(scale * unit(random));
      x.push_back(scale * unit(random));
      v.push_back(10.0 * unit(random));
      v.push_back(10.0 * unit(random));
    }
    // Particle 0 at (0.25, 0.5); 1 and 2 sit on it; 3 is 0.9e-12 m from it, 4 is 1.1e-12 m; 5 is NaN.
    x[0] = 0.25;
    x[1] = 0.5;
    x[2] = x[0];
    x[3] = x[1];
    x[4] = x[0];
    x[5] = x[1];
    x[6] = x[0] + 0.9e-12;
    x[7] = x[1];
    x[8] = x[0] + 1.1e-12;
    x[9] = x[1];
    x[10] = std::numeric_limits<double>::quiet_NaN();
    std::uniform_int_distribution<int> particle(0, particles - 1);
    for (size_t i = 0; i < n; ++i) {
      int a = particle(random), b = particle(random);
      if (i < 6) {
        static const int kPairs[6][2] = {{0, 1}, {1, 2}, {0, 3}, {0, 4}, {5, 0}, {4, 3}};
        a = kPairs[i][0];
        b = kPairs[i][1];
      }
      endA.push_back(2 * a);
      endB.push_back(2 * b);
      rest.push_back(i % 7 == 0 ? 0.0 : std::abs(unit(random)) * std::pow(10.0, 3.0 * unit(random)));
      ks.push_back(std::pow(10.0, 4.0 * unit(random)));
      kd.push_back(i % 5 == 0 ? 0.0 : std::abs(unit(random)));
    }
  }
  SpringArrays arrays() const { return {endA.data(), endB.data(), rest.data(), ks.data(), kd.data()}; }
};

}  // namespace

TEST_CASE("spring kernel: f_a = −[k_s(|l| − r)|l| + k_d l̇·l]/|l|² l, f_b = −f_a, 0 below 1e-12 m") {
  const RandomSprings s(257);
  std::vector<double> out(4 * s.endA.size());
  springForces(s.arrays(), s.x.data(), s.v.data(), out.data(), 0, s.endA.size());
  for (size_t i = 0; i < s.endA.size(); ++i) {
    const Vec2 l(s.x[size_t(s.endA[i])] - s.x[size_t(s.endB[i])],
                 s.x[size_t(s.endA[i]) + 1] - s.x[size_t(s.endB[i]) + 1]);
    const Vec2 ldot(s.v[size_t(s.endA[i])] - s.v[size_t(s.endB[i])],
                    s.v[size_t(s.endA[i]) + 1] - s.v[size_t(s.endB[i]) + 1]);
    CAPTURE(i);
    if (!l.allFinite()) {
      CHECK(std::isnan(out[4 * i]));
      continue;
    }
    Vec2 expected = Vec2::Zero();
    double scale = 0.0;  // the magnitude of the terms, which may cancel
    if (l.norm() >= kMinSpringLength) {
      const double len = l.norm();
      expected = -(s.ks[i] * (len - s.rest[i]) + s.kd[i] * ldot.dot(l) / len) * (l / len);
      scale = std::abs(s.ks[i] * (len - s.rest[i])) + std::abs(s.kd[i] * ldot.dot(l) / len);
    }
    const double tolerance = 1e-13 * scale;
    CHECK(std::abs(out[4 * i] - expected.x()) <= tolerance);
    CHECK(std::abs(out[4 * i + 1] - expected.y()) <= tolerance);
    CHECK(out[4 * i + 2] == -out[4 * i]);
    CHECK(out[4 * i + 3] == -out[4 * i + 1]);
  }
  // The named cases: both ends at one place, and 0.9e-12 m apart, exert nothing; 1.1e-12 m does.
  CHECK(out[4] == 0.0);
  CHECK(out[4 * 2] == 0.0);
  CHECK(out[4 * 3] != 0.0);
}

TEST_CASE("spring kernel: the AVX2 loop gives the scalar loop's bits, from any start and length") {
  const RandomSprings s(1031);
  std::vector<double> scalar(4 * s.endA.size()), simd(4 * s.endA.size());
  // Ranges that start and end off a multiple of four (the vector loop's remainder).
  for (const auto& [begin, end] : {std::pair<size_t, size_t>{0, 1031}, {3, 1030}, {5, 8}, {0, 4}, {7, 7}}) {
    CAPTURE(begin);
    CAPTURE(end);
    std::fill(scalar.begin(), scalar.end(), 7.0);
    std::fill(simd.begin(), simd.end(), 7.0);
    springForcesScalar(s.arrays(), s.x.data(), s.v.data(), scalar.data() + 4 * begin, begin, end);
    if (!springForcesAvx2(s.arrays(), s.x.data(), s.v.data(), simd.data() + 4 * begin, begin, end)) {
      return skipTest("this processor (or build) has no AVX2: only the scalar spring loop runs here");
    }
    CHECK(sameBits(scalar, simd));
  }
}

TEST_CASE("fused pass over the points: the same bits as each force's own loop, in the force order") {
  // The report's cloth with gravity and drag: grid springs, then two linear forces (the fused
  // kernel's case). The reference applies each force alone (Force::apply: for the springs, every
  // spring's values and then its own per-point sums) and forms [v, F/m] by hand. At 37² the
  // springs' values are computed all at once; at 200² (79,600 springs, 2.5 MiB of values, 10
  // chunks of points) each chunk computes those it needs (DampedSpringForce, chunk-local).
  for (int side : {37, 200}) {
    CAPTURE(side);
    SystemBuilder builder;
    auto& springs = builder.emplaceForce<DampedSpringForce>();
    addGrid(builder, springs, reportCloth(side, 0.05));
    builder.emplaceForce<GravityForce>(Vec2(0.3, -9.81));
    builder.emplaceForce<DragForce>(0.07);
    System system = builder.build();
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> jitter(-0.01, 0.01);
    for (Eigen::Index k = 0; k < system.state().size(); ++k) system.state()[k] += jitter(random);

    for (int threads : {1, 3}) {
      CAPTURE(threads);
      system.setThreads(threads);
      Eigen::VectorXd dydt;
      system.derivEval(system.state(), 0.0, dydt);

      const StateView s = system.view();
      ForceAccumulator acc;
      acc.resize(system.layout());
      for (const auto& force : system.forces()) force->apply(system.model(), s, 0.0, acc);
      const int points = system.layout().numPoints();
      std::vector<double> expected(size_t(4 * points)), actual(size_t(4 * points));
      for (int i = 0; i < points; ++i) {
        const Vec2 v = s.vel(i);
        const double invMass = system.model().invMass[size_t(i)];
        expected[size_t(2 * i)] = v.x();
        expected[size_t(2 * i + 1)] = v.y();
        expected[size_t(2 * points + 2 * i)] = acc.force[2 * i] * invMass;
        expected[size_t(2 * points + 2 * i + 1)] = acc.force[2 * i + 1] * invMass;
      }
      std::memcpy(actual.data(), dydt.data(), actual.size() * sizeof(double));
      CHECK(sameBits(expected, actual));
    }
  }
}
