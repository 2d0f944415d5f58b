#pragma once
// Gravity: f_i += m_i g on every point, particles and rigid bodies alike.
// Potential: U = −Σ m_i g·x_i over the movable points (fixed ones only add a constant).

#include "core/force.hpp"

namespace particles {

class GravityForce final : public Force {
 public:
  explicit GravityForce(const Vec2& g) : g_(g) {}
  const Vec2& g() const { return g_; }

  std::string_view kind() const override { return "gravity"; }
  void apply(const Model& model, const StateView& s, double t, ForceAccumulator& acc) const override;
  bool actsPointwise() const override { return true; }
  void applyToPoints(const Model& model, const StateView& s, double t, double* force, int begin,
                     int end) const override;
  PointwiseTerm pointwiseTerm() const override { return {.kind = PointwiseTerm::Kind::perMass, .a = g_}; }
  double potentialEnergy(const Model& model, const StateView& s, double t) const override;
  void draw(const StateView&, double, Drawing&, WorkerPool*) const override {}  // nothing to show
  // M |g| (extent + 1 m): the work gravity does when everything falls across the scene.
  double energyScale(const Model& model, const StateView& s) const override;

 private:
  Vec2 g_;
};

// How scenario files write it (`{type: gravity, g}`).
const KindSpec& gravityKind();

}  // namespace particles
