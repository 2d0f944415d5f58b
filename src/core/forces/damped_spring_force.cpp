#include "core/forces/damped_spring_force.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/forces/spring_force_kernel.hpp"
#include "core/group_by_bucket.hpp"
#include "core/system.hpp"

namespace particles {

namespace {
// Springs per chunk of the threaded loops: enough work that a hand-over is small beside it (a
// chunk's time, from the spring loop's per spring: bench/README.md, "derivEval on the cloth").
constexpr size_t kSpringChunk = 8192;
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

double DampedSpringForce::length(const StateView& s, size_t i) const {
  if (allParticles_) {
    // The particles' positions straight from the state (the stability study asks every step).
    const double* x = s.vector().data();
    return (Vec2(x[endA_[i]], x[endA_[i] + 1]) - Vec2(x[endB_[i]], x[endB_[i] + 1])).norm();
  }
  return (endpointPosition(s, a_[i]) - endpointPosition(s, b_[i])).norm();
}

double DampedSpringForce::strain(const StateView& s, size_t i) const {
  const double len = length(s, i);
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

void DampedSpringForce::buildIncidence(int points) const {
  const size_t n = a_.size();
  // Each point's spring ends, in spring order: end e = 2·spring + (1 at its b end), whose value
  // (f_a, or −f_a at a b end) is the pair at 2e.
  std::vector<int> pointOfEnd(2 * n);
  for (size_t i = 0; i < n; ++i) {
    pointOfEnd[2 * i] = endA_[i] / 2;
    pointOfEnd[2 * i + 1] = endB_[i] / 2;
  }
  groupByBucket(size_t(points), pointOfEnd, endStart_, endOf_);
  for (int& end : endOf_) end *= 2;

  // Each chunk's springs, as runs of consecutive ones; chunk-local when together they are at
  // most a quarter more than the springs and no chunk has more than kMaxRuns runs.
  constexpr size_t kMaxRuns = 16;
  const size_t chunks = chunkCount(size_t(points), kPointChunk);
  chunkRuns_.assign(1, 0);
  runFirst_.clear();
  runEnd_.clear();
  localEnds_.resize(endOf_.size());
  size_t computed = 0, mostRuns = 0;
  std::vector<int> needed;
  for (size_t c = 0; c < chunks; ++c) {
    const auto from = endOf_.begin() + endStart_[c * kPointChunk];
    const auto to = endOf_.begin() + endStart_[std::min(size_t(points), (c + 1) * kPointChunk)];
    needed.clear();
    for (auto e = from; e != to; ++e) needed.push_back(*e / 4);
    std::sort(needed.begin(), needed.end());
    needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
    for (size_t k = 0; k < needed.size(); ++k) {
      if (k == 0 || needed[k] != needed[k - 1] + 1) {
        runFirst_.push_back(size_t(needed[k]));
        runEnd_.push_back(size_t(needed[k]));
      }
      ++runEnd_.back();
    }
    mostRuns = std::max(mostRuns, runFirst_.size() - chunkRuns_.back());
    chunkRuns_.push_back(runFirst_.size());
    computed += needed.size();
    // A spring's place in the chunk's concatenated runs is its rank among the springs it needs.
    for (auto e = from; e != to; ++e) {
      const long rank = std::lower_bound(needed.begin(), needed.end(), *e / 4) - needed.begin();
      localEnds_[size_t(e - endOf_.begin())] = int(4 * rank + (*e & 2));
    }
  }
  // Values that fit in a core's cache (its L2: 1–2 MiB on today's servers) come back from it
  // anyway: chunk-local lost on the 100² cloth's 0.6 MiB and won on the 316² cloth's 6.4 MiB
  // (bench/README.md, "Chunk-local springs").
  constexpr size_t kCacheBytes = size_t(1) << 20;
  chunkLocal_ = 4 * sizeof(double) * n > kCacheBytes && 4 * computed <= 5 * n && mostRuns <= kMaxRuns;
  if (!chunkLocal_) {
    chunkRuns_.clear();
    runFirst_.clear();
    runEnd_.clear();
    localEnds_.clear();
  }
  springForce_.assign(chunkLocal_ ? 0 : 4 * n, 0.0);
}

void DampedSpringForce::preparePoints(const Model& model, const StateView& s, double, WorkerPool* pool) const {
  const size_t n = a_.size();
  const int points = model.layout.numPoints();
  if (endStart_.size() != size_t(points) + 1) buildIncidence(points);
  positions_ = s.vector().data();
  velocities_ = positions_ + s.layout().velocityOffset();
  if (chunkLocal_) return;  // computed chunk by chunk, in valuesFor
  const SpringArrays springs{endA_.data(), endB_.data(), rest_.data(), ks_.data(), kd_.data()};
  double* out = springForce_.data();
  forChunks(pool, n, kSpringChunk, [&](size_t begin, size_t end) {
    springForces(springs, positions_, velocities_, out + 4 * begin, begin, end);
  });
}

GatherValues DampedSpringForce::valuesFor(int begin, int end, std::vector<double>& scratch) const {
  if (!chunkLocal_) return {springForce_.data(), endOf_.data()};
  const SpringArrays springs{endA_.data(), endB_.data(), rest_.data(), ks_.data(), kd_.data()};
  const size_t points = endStart_.size() - 1;
  if (size_t(begin) % kPointChunk == 0 && size_t(end) == std::min(points, size_t(begin) + kPointChunk)) {
    // One of the pass's chunks: its runs, one after the other.
    const size_t chunk = size_t(begin) / kPointChunk;
    size_t length = 0;
    for (size_t r = chunkRuns_[chunk]; r < chunkRuns_[chunk + 1]; ++r) length += runEnd_[r] - runFirst_[r];
    scratch.resize(4 * length);
    size_t at = 0;
    for (size_t r = chunkRuns_[chunk]; r < chunkRuns_[chunk + 1]; ++r) {
      springForces(springs, positions_, velocities_, scratch.data() + 4 * at, runFirst_[r], runEnd_[r]);
      at += runEnd_[r] - runFirst_[r];
    }
    return {scratch.data(), localEnds_.data()};
  }
  // Another range (apply's whole system): every spring, in spring order.
  scratch.resize(4 * a_.size());
  springForces(springs, positions_, velocities_, scratch.data(), 0, a_.size());
  return {scratch.data(), endOf_.data()};
}

void DampedSpringForce::applyToPoints(const Model&, const StateView&, double, double* force, int begin, int end) const {
  std::vector<double> scratch;
  const GatherValues values = valuesFor(begin, end, scratch);
  const int* start = endStart_.data();
  for (int p = begin; p < end; ++p) {
    double fx = force[2 * p], fy = force[2 * p + 1];
    for (int k = start[p]; k < start[p + 1]; ++k) {
      const double* value = values.values + values.entries[k];
      fx += value[0];
      fy += value[1];
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
    // Every spring's pair at a fixed place (zeros for one of length ~0, so that the pattern
    // stays), filled by chunks of springs on the threads.
    const size_t n = a_.size();
    const size_t p0 = out.pairs.size();
    out.pairs.resize(p0 + n);
    const double* y = s.vector().data();
    forChunks(out.pool, n, kSpringChunk, [&](size_t begin, size_t end) {
      Eigen::Matrix2d k, d;
      for (size_t i = begin; i < end; ++i) {
        const int ia = endA_[i], ib = endB_[i];
        blocksOf(i, Vec2(y[ia] - y[ib], y[ia + 1] - y[ib + 1]), k, d);
        out.pairs[p0 + i] = JacobianPair(ia / 2, ib / 2, k, d);
      }
    });
    return;
  }
  Eigen::Matrix2d k, d;
  for (size_t i = 0; i < a_.size(); ++i) {
    if (!blocksOf(i, endpointPosition(s, a_[i]) - endpointPosition(s, b_[i]), k, d)) continue;
    out.pairs.emplace_back(a_[i].point(layout), b_[i].point(layout), k, d);
  }
}

double DampedSpringForce::potentialEnergy(const Model&, const StateView& s, double) const {
  double u = 0.0;
  for (size_t i = 0; i < a_.size(); ++i) {
    const double stretch = length(s, i) - rest_[i];
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

void DampedSpringForce::draw(const StateView& s, double, Drawing& out, WorkerPool* pool) const {
  const size_t first = out.springs.size();
  out.springs.resize(first + size());
  forChunks(pool, size(), kSpringChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      out.springs[first + i] = {endpointPosition(s, a_[i]), endpointPosition(s, b_[i]), strain(s, i), rest_[i], ks_[i]};
    }
  });
}

bool DampedSpringForce::addSpringTopology(Drawing::SpringTopology& out) const {
  if (!allParticles_) return false;
  out.ends.reserve(out.ends.size() + 2 * size());
  for (size_t i = 0; i < size(); ++i) out.ends.insert(out.ends.end(), {std::uint32_t(a_[i].particle), std::uint32_t(b_[i].particle)});
  out.rest.insert(out.rest.end(), rest_.begin(), rest_.end());
  out.stiffness.insert(out.stiffness.end(), ks_.begin(), ks_.end());
  return true;
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
