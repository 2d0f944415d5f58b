#pragma once
// Viscous drag: f_i −= k_d v_i on every point (docs/physics.md §4). Dissipative: no potential energy.
// Jacobian for backward Euler: ∂f_i/∂v_i = −k_d I (the angular term is explicit).
// An optional angular term τ_j −= k_ω ω_j damps rigid-body spin the same way.

#include "core/force.hpp"

namespace particles {

class DragForce final : public Force {
 public:
  explicit DragForce(double kd, double angularKd = 0.0) : kd_(kd), angularKd_(angularKd) {}
  double kd() const { return kd_; }

  std::string_view kind() const override { return "drag"; }
  void apply(const Model& model, const StateView& s, double t, ForceAccumulator& acc) const override;
  // Point by point when there is no angular term (which acts on the torques).
  bool actsPointwise() const override { return angularKd_ == 0.0; }
  void applyToPoints(const Model& model, const StateView& s, double t, double* force, int begin,
                     int end) const override;
  PointwiseTerm pointwiseTerm() const override { return {.kind = PointwiseTerm::Kind::perVelocity, .c = kd_}; }
  double potentialEnergy(const Model&, const StateView&, double) const override { return 0.0; }
  double energyScale(const Model&, const StateView&) const override { return 0.0; }
  bool isDissipative() const override { return true; }
  void draw(const StateView&, double, Drawing&, WorkerPool*) const override {}  // nothing to show
  void addJacobians(const Model& model, const StateView& s, double t, ForceJacobians& out) const override;

 private:
  double kd_;
  double angularKd_;
};

// How scenario files write it (`{type: drag, kd, angular}`).
const KindSpec& dragKind();

}  // namespace particles
