#pragma once
// A force object (docs/physics.md §4): adds to the accumulators given a state and a time, and reports the
// potential energy it stores so energy can be booked by source.

#include <cstddef>
#include <string_view>
#include <vector>

#include "core/drawing.hpp"
#include "core/force_accumulator.hpp"
#include "core/force_jacobians.hpp"
#include "core/kind.hpp"
#include "core/model.hpp"
#include "core/worker_pool.hpp"

namespace particles {

// A gathered term's values for points [begin, end): point i's k-th entry (k ∈ [start[i],
// start[i+1]) of the term) adds the pair values[entries[k]], values[entries[k] + 1].
struct GatherValues {
  const double* values = nullptr;
  const int* entries = nullptr;
};

// What computes a gathered term's values (DampedSpringForce: each spring's (f_a, −f_a)), for one
// chunk of points at a time, so that they are read while still in the core's cache; `scratch` is
// the calling thread's own. Called from several threads at once on different chunks.
class PointGatherSource {
 public:
  virtual GatherValues valuesFor(int begin, int end, std::vector<double>& scratch) const = 0;

 protected:
  ~PointGatherSource() = default;
};

// How a force that acts point by point adds to point i's force, when it has one of the two shapes
// Witkin & Baraff's forces take (docs/physics.md §4), so that the fused pass over the points
// (System::derivEval) can run a run of such forces as one loop with the running force in
// registers instead of one loop per force:
//   unary, linear:  f_i += m_i a           (gravity: a = g)          kind perMass
//                   f_i −= c v_i           (drag: c = k_d)           kind perVelocity
//   n-ary, gathered: f_i += Σ_{k ∈ [start[i], start[i+1])} the pair of entry k (GatherValues)
//                   (springs: each spring's f_a and f_b = −f_a, at the ends that are i, in spring
//                   order), kind gather
// Each describes exactly the additions applyToPoints makes, in the same order, so either path
// gives the same bits.
struct PointwiseTerm {
  enum class Kind { none, perMass, perVelocity, gather };
  Kind kind = Kind::none;
  Vec2 a = Vec2::Zero();  // perMass
  double c = 0.0;         // perVelocity
  // gather: per point, the range of its entries; the values from source, chunk by chunk
  const int* start = nullptr;
  const PointGatherSource* source = nullptr;
};

class Force {
 public:
  virtual ~Force() = default;
  // The kind's name as scenario files spell it ("gravity", "drag", "spring", "mouse"); it also
  // labels the force's potential energy in energy reports.
  virtual std::string_view kind() const = 0;
  virtual void apply(const Model& model, const StateView& s, double t, ForceAccumulator& acc) const = 0;
  // A force that acts point by point (gravity, drag, springs between particles) can instead be
  // applied chunk by chunk of points, fused with its neighbours in the force order into one pass
  // over the points on the System's threads (System::derivEval). Such a force returns true here;
  // preparePoints does the work that is not per point first (a spring's force, per spring, on the
  // pool), then applyToPoints adds the force on points [begin, end) to `force` (2 per point),
  // touching no other point, with the same additions in the same order as apply.
  virtual bool actsPointwise() const { return false; }
  virtual void preparePoints(const Model&, const StateView&, double, WorkerPool*) const {}
  virtual void applyToPoints(const Model&, const StateView&, double, double* /*force*/, int /*begin*/,
                             int /*end*/) const {}
  // The same additions described by shape (above), valid after preparePoints; none by default.
  virtual PointwiseTerm pointwiseTerm() const { return {}; }
  // Potential energy stored by this force, joules; zero for dissipative forces.
  virtual double potentialEnergy(const Model& model, const StateView& s, double t) const = 0;
  // An energy this force can plausibly put into the system, joules: the explosion guard's yardstick.
  virtual double energyScale(const Model& model, const StateView& s) const = 0;
  // How many elements this object holds (springs in a spring set; 1 for most forces), for summaries.
  virtual size_t count() const { return 1; }
  // True for a set of springs between points (count() of them, each with a rest length): the
  // summaries' spring count adds up these.
  virtual bool isSpringSet() const { return false; }
  // The largest current length over rest length of the force's elastic elements (springs), or 0
  // when it has none: the stability study's "overstretched" criterion.
  virtual double maxStretchRatio(const StateView&) const { return 0.0; }
  // True for a force whose potential depends on time itself (a scripted mouse): moving it does
  // work on the system, which energy budgets count as put in from outside.
  virtual bool isTimeDependent() const { return false; }
  // True for a force that only takes energy out (drag): it stores none, so energy reports skip it.
  virtual bool isDissipative() const { return false; }
  // Adds what this force shows (springs, cursors) to the frame's drawing. A force of many items
  // may fill its part in chunks on `pool` (null: serial), as its other loops do.
  virtual void draw(const StateView& s, double t, Drawing& out, WorkerPool* pool) const = 0;
  // A spring set's springs (what its draw() adds) by their ends' particle indices, appended to
  // `out` in draw()'s order (Drawing::SpringTopology); false, adding nothing, when one of them has
  // an end on a body, which only draw() can show. When every force gives its springs so, System::draw
  // with SpringDetail::topology does not call a spring set's draw(). A force that is no spring set
  // draws no springs: it adds nothing.
  virtual bool addSpringTopology(Drawing::SpringTopology& out) const {
    (void)out;
    return !isSpringSet();
  }
  // Adds ∂f/∂x and ∂f/∂v at (s, t) for the implicit integrator (core/force_jacobians.hpp: symmetric,
  // negative semi-definite blocks). Nothing by default: the force is then taken explicitly.
  virtual void addJacobians(const Model&, const StateView&, double, ForceJacobians&) const {}
  // Throws std::invalid_argument when the force refers to a particle or body the layout lacks.
  virtual void validate(const StateLayout&) const {}
};

}  // namespace particles
