#pragma once
// The fused pass of System::derivEval over a run of forces that act point by point and each
// describe themselves as a PointwiseTerm (core/force.hpp), the n-ary (gathered) ones first, which
// is how scenarios come (grid springs, then gravity and drag). For each point it starts the force
// at 0 or at what the accumulator holds, adds the terms in the force order with the running sum
// in registers, stores it, and, when nothing else comes before stage 5, writes d/dt [x, v] =
// [v, F/m] at once: one loop over the points instead of one per force and one for stage 5, with
// the same additions in the same order as the forces' applyToPoints (so the same bits).

#include <memory>
#include <span>
#include <vector>

#include "core/force.hpp"

namespace particles {

class PointwiseRun {
 public:
  // The terms of a run of forces; false when one of them has no term, or a gathered one comes
  // after a linear one (then the caller takes the forces' applyToPoints chunk by chunk).
  bool collect(std::span<const std::unique_ptr<Force>> forces);

  struct Points {
    double* force;           // 2 per point, read (unless cleared) and written
    const double* velocity;  // 2 per point
    const double* mass;
    const double* invMass;
    double* derivative;  // dy/dt, or null: stage 5 comes later
    long velocityRow;    // where dv/dt starts in dy/dt: 2 · points
  };
  // Points [begin, end); `clear`: the accumulator is not yet cleared (the force starts at 0).
  void run(const Points& points, int begin, int end, bool clear) const;

 private:
  std::vector<PointwiseTerm> gathers_, linears_;
};

}  // namespace particles
