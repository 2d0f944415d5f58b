#include "core/forces/damped_spring_force.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/forces/spring_force_kernel.hpp"
#include "core/group_by_bucket.hpp"
#include "core/system.hpp"

namespace particles {

namespace {
constexpr size_t kSpringChunk = 8192;  // springs per chunk of the threaded loops: ~40 µs of work
}

void DampedSpringForce::add(const SpringSpec& spring) {
  a_.push_back(spring.a);
  b_.push_back(spring.b);
  rest_.push_back(spring.rest);
  ks_.push_back(spring.ks);
  kd_.push_back(spring.kd);
  allParticles_ = allParticles_ && spring.a.isParticle() && spring.b.isParticle();
  endA_.push_back(2 * spring.a.particle);
  endB_.push_back(2 * spring.b.particle);
  endStart_.clear();
}

void DampedSpringForce::reserve(size_t n) {
  a_.reserve(n);
  b_.reserve(n);
  rest_.reserve(n);
  ks_.reserve(n);
  kd_.reserve(n);
  endA_.reserve(n);
  endB_.reserve(n);
}

double DampedSpringForce::strain(const StateView& s, size_t i) const {
  const double len = (endpointPosition(s, a_[i]) - endpointPosition(s, b_[i])).norm();
  return rest_[i] > 0.0 ? len / rest_[i] - 1.0 : 0.0;
}

void DampedSpringForce::apply(const Model& model, const StateView& s, double t, ForceAccumulator& acc) const {
  if (allParticles_) {
    preparePoints(model, s, t, nullptr);
    applyToPoints(model, s, t, acc.force.data(), 0, model.layout.numPoints());
    return;
  }
  for (size_t i = 0; i < a_.size(); ++i) {
    const Vec2 l = endpointPosition(s, a_[i]) - endpointPosition(s, b_[i]);
    const double len = l.norm();
    if (len < kMinSpringLength) continue;
    const Vec2 ldot = endpointVelocity(s, a_[i]) - endpointVelocity(s, b_[i]);
    const Vec2 fa = -(ks_[i] * (len - rest_[i]) + kd_[i] * ldot.dot(l) / len) * (l / len);
    applyForceAt(s, a_[i], fa, acc);
    applyForceAt(s, b_[i], -fa, acc);
  }
}

void DampedSpringForce::preparePoints(const Model& model, const StateView& s, double, WorkerPool* pool) const {
  const size_t n = a_.size();
  const int points = model.layout.numPoints();
  if (endStart_.size() != size_t(points) + 1) {
    // Each point's spring ends, in spring order: end e = 2·spring + (1 at its b end), whose
    // value (f_a, or −f_a at a b end) is at springForce_[2e].
    std::vector<int> pointOfEnd(2 * n);
    for (size_t i = 0; i < n; ++i) {
      pointOfEnd[2 * i] = endA_[i] / 2;
      pointOfEnd[2 * i + 1] = endB_[i] / 2;
    }
    groupByBucket(size_t(points), pointOfEnd, endStart_, endOf_);
    for (int& end : endOf_) end *= 2;
    springForce_.resize(4 * n);
  }
  const double* x = s.vector().data();
  const double* v = x + s.layout().velocityOffset();
  const SpringArrays springs{endA_.data(), endB_.data(), rest_.data(), ks_.data(), kd_.data()};
  double* out = springForce_.data();
  forChunks(pool, n, kSpringChunk, [&](size_t begin, size_t end) { springForces(springs, x, v, out, begin, end); });
}

void DampedSpringForce::applyToPoints(const Model&, const StateView&, double, double* force, int begin, int end) const {
  const int* start = endStart_.data();
  const int* ends = endOf_.data();
  const double* springForce = springForce_.data();
  for (int p = begin; p < end; ++p) {
    double fx = force[2 * p], fy = force[2 * p + 1];
    for (int k = start[p]; k < start[p + 1]; ++k) {
      fx += springForce[ends[k]];
      fy += springForce[ends[k] + 1];
    }
    force[2 * p] = fx;
    force[2 * p + 1] = fy;
  }
}

void DampedSpringForce::addJacobians(const Model& model, const StateView& s, double, ForceJacobians& out) const {
  const StateLayout& layout = model.layout;
  // The blocks of spring i (docs above).
  auto blocksOf = [&](size_t i, Vec2 l, Eigen::Matrix2d& k, Eigen::Matrix2d& d) {
    const double len = l.norm();
    if (len < kMinSpringLength) {
      k.setZero();
      d.setZero();
      return false;
    }
    const Vec2 u = l / len;
    const Eigen::Matrix2d uu = u * u.transpose();
    const double transverse = std::max(0.0, 1.0 - rest_[i] / len);
    k = -ks_[i] * (uu + transverse * (Eigen::Matrix2d::Identity() - uu));
    d = -kd_[i] * uu;
    return true;
  };
  if (allParticles_) {
    // Every spring's entries at a fixed place (zeros for one of length ~0, so that the pattern
    // stays), filled by chunks of springs on the threads.
    const size_t n = a_.size();
    const size_t k0 = out.dfdx.size(), d0 = out.dfdv.size();
    constexpr size_t kEntries = ForceJacobians::kPairEntries;
    out.dfdx.resize(k0 + kEntries * n);
    out.dfdv.resize(d0 + kEntries * n);
    const double* y = s.vector().data();
    forChunks(out.pool, n, kSpringChunk, [&](size_t begin, size_t end) {
      Eigen::Matrix2d k, d;
      for (size_t i = begin; i < end; ++i) {
        const int ia = endA_[i], ib = endB_[i];
        blocksOf(i, Vec2(y[ia] - y[ib], y[ia + 1] - y[ib + 1]), k, d);
        ForceJacobians::writePair(&out.dfdx[k0 + kEntries * i], ia / 2, ib / 2, k);
        ForceJacobians::writePair(&out.dfdv[d0 + kEntries * i], ia / 2, ib / 2, d);
      }
    });
    return;
  }
  Eigen::Matrix2d k, d;
  for (size_t i = 0; i < a_.size(); ++i) {
    if (!blocksOf(i, endpointPosition(s, a_[i]) - endpointPosition(s, b_[i]), k, d)) continue;
    const int pa = a_[i].point(layout), pb = b_[i].point(layout);
    ForceJacobians::addPair(out.dfdx, pa, pb, k);
    if (kd_[i] != 0.0) ForceJacobians::addPair(out.dfdv, pa, pb, d);
  }
}

double DampedSpringForce::potentialEnergy(const Model&, const StateView& s, double) const {
  double u = 0.0;
  for (size_t i = 0; i < a_.size(); ++i) {
    const double stretch = (endpointPosition(s, a_[i]) - endpointPosition(s, b_[i])).norm() - rest_[i];
    u += 0.5 * ks_[i] * stretch * stretch;
  }
  return u;
}

double DampedSpringForce::energyScale(const Model& model, const StateView& s) const {
  // Energy stored now, plus what each spring would hold stretched by its own rest length.
  double e = potentialEnergy(model, s, 0.0);
  for (size_t i = 0; i < a_.size(); ++i) e += 0.5 * ks_[i] * rest_[i] * rest_[i];
  return e;
}

void DampedSpringForce::validate(const StateLayout& layout) const {
  for (size_t i = 0; i < a_.size(); ++i) {
    checkEndpoint(layout, a_[i], "spring");
    checkEndpoint(layout, b_[i], "spring");
  }
}

double DampedSpringForce::maxStretchRatio(const StateView& s) const {
  double worst = 0.0;
  for (size_t i = 0; i < size(); ++i) {
    if (rest_[i] > 0.0) worst = std::max(worst, 1.0 + strain(s, i));
  }
  return worst;
}

void DampedSpringForce::draw(const StateView& s, double, Drawing& out) const {
  out.springs.reserve(out.springs.size() + size());
  for (size_t i = 0; i < size(); ++i) {
    out.springs.push_back({endpointPosition(s, a_[i]), endpointPosition(s, b_[i]), strain(s, i)});
  }
}

namespace {

bool sameEndpoint(const Endpoint& a, const Endpoint& b) {
  return a.particle == b.particle && a.body == b.body && a.anchor == b.anchor;
}

// `a` and `b` may each be one point or a list; two lists pair up element by element, and a single
// point pairs with every point of a list.
void buildSprings(const KindArgs& args, SystemBuilder& out) {
  const std::vector<Endpoint> a = args.points("a");
  const std::vector<Endpoint> b = args.points("b");
  if (a.size() != 1 && b.size() != 1 && a.size() != b.size()) {
    args.fail("b", fmt::format("'a' names {} points and 'b' names {}; lists must have the same length (or one side "
                               "a single point)",
                               a.size(), b.size()));
  }
  const bool hasRest = args.has("rest");
  const double rest = hasRest ? args.number("rest") : 0.0;
  const double ks = args.number("ks");
  const double kd = args.number("kd");
  // Kept apart from the grids' springs, which then stay on the all-particle fast path.
  auto& springs = out.sharedForce<DampedSpringForce>("explicit springs");
  const size_t n = std::max(a.size(), b.size());
  for (size_t i = 0; i < n; ++i) {
    const Endpoint& ea = a[a.size() == 1 ? 0 : i];
    const Endpoint& eb = b[b.size() == 1 ? 0 : i];
    if (sameEndpoint(ea, eb)) args.fail("b", fmt::format("a spring joins {} to itself", args.describe(ea)));
    springs.add({ea, eb, hasRest ? rest : (args.initialPosition(ea) - args.initialPosition(eb)).norm(), ks, kd});
  }
}

}  // namespace

const KindSpec& springKind() {
  static const KindSpec spec{
      .section = "forces",
      .type = "spring",
      .summary = "damped springs f_a = −[k_s(|l| − r) + k_d (l̇·l)/|l|] l/|l|, f_b = −f_a",
      .params = {{.key = "a", .type = ParamType::endpoints, .required = true, .note = "particles or body anchors"},
                 {.key = "b", .type = ParamType::endpoints, .required = true, .note = "particles or body anchors"},
                 {.key = "rest", .type = ParamType::number, .unit = "m", .defaultText = "the current distance",
                  .min = Bound{0.0, true}},
                 {.key = "ks", .type = ParamType::number, .unit = "N/m", .required = true, .min = Bound{0.0, true}},
                 {.key = "kd", .type = ParamType::number, .unit = "N·s/m", .defaultNumber = 0.0,
                  .min = Bound{0.0, true}}},
      .build = buildSprings,
  };
  return spec;
}

}  // namespace particles
