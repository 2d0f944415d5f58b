#pragma once
// Damped springs (docs/physics.md §4), stored as flat arrays: one object holds any number of springs.
// With l = x_a − x_b, rest length r, stiffness k_s and damping k_d:
//   f_a = −[ k_s (|l| − r) + k_d (l̇·l)/|l| ] l/|l|,   f_b = −f_a
// Ends are particles or anchors on rigid bodies (then x and l̇ use the anchor's world position and
// velocity, and the force also gives a torque, docs/physics.md §7).
// Potential: U = ½ k_s (|l| − r)² per spring.
// When |l| falls below 1e-12 m the direction is undefined and the spring exerts no force.
// Between particles only (the cloth's case), the force is found in two steps that threads can
// share without ever adding into the same number: every spring's (f_a, −f_a)
// (core/forces/spring_force_kernel.hpp), then every particle's sum of f_a over the springs whose a
// end it is and −f_a over those whose b end it is, in spring order: the same additions in the
// same order as one loop over the springs that adds f_a at a and −f_a at b. When each chunk of
// points needs few springs besides its own share, in a few runs of consecutive springs (a grid's:
// its rows' horizontal springs, and its rows' vertical ones and those from the row above), each
// chunk computes the springs it needs just before summing them, so that the values are read from
// the core's cache rather than from memory (the springs between two chunks, 7.6 % of the 316²
// cloth's, are computed twice); otherwise every spring's values are computed first, in chunks
// of springs (preparePoints).
// Jacobians for backward Euler (Baraff & Witkin 1998 §5.2), with l̂ = l/|l|:
//   ∂f_a/∂x_a = −k_s [ l̂l̂ᵀ + max(0, 1 − r/|l|) (I − l̂l̂ᵀ) ],   ∂f_a/∂v_a = −k_d l̂l̂ᵀ
// and [b −b; −b b] over the two ends. The exact transverse term (1 − r/|l|) turns positive
// definite when the spring is compressed (|l| < r: buckling), which would break the SPD matrix CG
// needs, so it is clamped at 0 (in the Jacobian only; the force keeps it); the damping's
// dependence on position is dropped, as Baraff & Witkin do. An anchor on a body couples through
// the body's centre (its translation); the rotation is explicit (docs/physics.md §3).

#include <vector>

#include "core/endpoint.hpp"
#include "core/force.hpp"

namespace particles {

struct SpringSpec {
  Endpoint a, b;
  double rest;  // m, ≥ 0
  double ks;    // N/m, ≥ 0
  double kd;    // N·s/m, ≥ 0
};

class DampedSpringForce final : public Force, private PointGatherSource {
 public:
  void add(const SpringSpec& spring);
  void reserve(size_t n);
  size_t size() const { return a_.size(); }
  SpringSpec spring(size_t i) const { return {a_[i], b_[i], rest_[i], ks_[i], kd_[i]}; }
  // Current length of spring i.
  double length(const StateView& s, size_t i) const;
  // Current length over rest length minus one (positive: stretched), for drawing and checks.
  double strain(const StateView& s, size_t i) const;

  std::string_view kind() const override { return "spring"; }
  size_t count() const override { return size(); }
  bool isSpringSet() const override { return true; }
  double maxStretchRatio(const StateView& s) const override;
  void apply(const Model& model, const StateView& s, double t, ForceAccumulator& acc) const override;
  bool actsPointwise() const override { return allParticles_; }
  void preparePoints(const Model& model, const StateView& s, double t, WorkerPool* pool) const override;
  void applyToPoints(const Model& model, const StateView& s, double t, double* force, int begin,
                     int end) const override;
  PointwiseTerm pointwiseTerm() const override {
    return {.kind = PointwiseTerm::Kind::gather, .start = endStart_.data(), .source = this};
  }
  double potentialEnergy(const Model& model, const StateView& s, double t) const override;
  double energyScale(const Model& model, const StateView& s) const override;
  void draw(const StateView& s, double t, Drawing& out, WorkerPool* pool) const override;
  bool addSpringTopology(Drawing::SpringTopology& out) const override;
  void addJacobians(const Model& model, const StateView& s, double t, ForceJacobians& out) const override;
  void validate(const StateLayout& layout) const override;

 private:
  std::vector<Endpoint> a_, b_;
  std::vector<double> rest_, ks_, kd_;
  bool allParticles_ = true;  // every end is a particle: the hot loop skips anchor kinematics
  // The particle-only path's arrays: each spring's ends as offsets 2·particle, and per point the
  // springs that touch it (2·spring, +1 at its b end), in spring order, from endStart_[p].
  std::vector<int> endA_, endB_;
  mutable std::vector<int> endStart_, endOf_;  // endOf_: 4·spring, + 2 at its b end
  // Chunk-local values (see the top): chunk c of kPointChunk points computes the runs of springs
  // [runFirst_[r], runEnd_[r]) for r ∈ [chunkRuns_[c], chunkRuns_[c + 1]), one after the other,
  // and its points' entries are localEnds_ (as endOf_, counted in that concatenation).
  mutable bool chunkLocal_ = false;
  mutable std::vector<size_t> chunkRuns_, runFirst_, runEnd_;
  mutable std::vector<int> localEnds_;
  mutable std::vector<double> springForce_;    // (f_a, −f_a) per spring, when not chunk-local
  mutable const double* positions_ = nullptr;  // the state preparePoints was given
  mutable const double* velocities_ = nullptr;

  // Lays out endStart_, endOf_ and the chunk-local runs for `points` points.
  void buildIncidence(int points) const;
  GatherValues valuesFor(int begin, int end, std::vector<double>& scratch) const override;
};

// How scenario files write it (`{type: spring, a, b, rest, ks, kd}`: every explicit spring joins one shared DampedSpringForce).
const KindSpec& springKind();

}  // namespace particles
