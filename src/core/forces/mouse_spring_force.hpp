#pragma once
// The scripted mouse (our off-line form of mouse interaction, docs/physics.md §4): while from ≤ t < to,
// a zero-rest-length spring pulls the grabbed endpoint towards a target m(t) moving along a
// polyline at constant speed (arc length proportional to time):
//   f = −k_s (x − m(t)),   U = ½ k_s |x − m(t)|²
// No damping, as in the report. A one-point path holds the target still.
// Jacobian for backward Euler while active: ∂f/∂x = −k_s I on the grabbed point (through a body's
// centre for an anchor; the target's motion is taken at the step's start).

#include <vector>

#include "core/endpoint.hpp"
#include "core/force.hpp"

namespace particles {

struct MouseScript {
  Endpoint grab;
  double from;             // s
  double to;               // s, > from
  std::vector<Vec2> path;  // at least one point, metres
  double ks;               // N/m
};

class MouseSpringForce final : public Force {
 public:
  explicit MouseSpringForce(MouseScript script);
  const MouseScript& script() const { return script_; }
  bool activeAt(double t) const { return t >= script_.from && t < script_.to; }
  // m(t): the target point at time t (clamped to the path's ends outside [from, to]).
  Vec2 target(double t) const;
  // A program moving the mouse (the library's Simulation::setMouseTarget): from `from` on, the
  // spring holds its point at `target`, the script's path and window replaced, until release.
  void holdAt(Vec2 target, double from);
  // Lets go at `at`: inactive from then on.
  void release(double at);

  std::string_view kind() const override { return "mouse"; }
  bool isTimeDependent() const override { return true; }
  void apply(const Model& model, const StateView& s, double t, ForceAccumulator& acc) const override;
  double potentialEnergy(const Model& model, const StateView& s, double t) const override;
  double energyScale(const Model& model, const StateView& s) const override;
  void addJacobians(const Model& model, const StateView& s, double t, ForceJacobians& out) const override;
  // The cursor and its line while the script holds its point.
  void draw(const StateView& s, double t, Drawing& out, WorkerPool* pool) const override;
  void validate(const StateLayout& layout) const override;

 private:
  MouseScript script_;
  std::vector<double> cumulativeLength_;  // arc length at each path point
};

// How scenario files write it (the `mouse` section: `{grab, from, to, path, ks}`).
const KindSpec& mouseKind();

}  // namespace particles
