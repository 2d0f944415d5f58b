#pragma once
// A scalar holonomic constraint C(q) = 0 on particle positions (docs/physics.md §5). Each kind reports C,
// Ċ and the non-zero 2-blocks of its Jacobian row J = ∂C/∂q and of J̇, for at most two particles.
// The solver (constraint_solver.hpp) turns the rows into J W Jᵀ λ = −J̇q̇ − J W Q − k_s C − k_d Ċ.

#include <array>
#include <string_view>
#include <vector>

#include "core/drawing.hpp"
#include "core/kind.hpp"
#include "core/state.hpp"

namespace particles {

struct ConstraintRow {
  double C = 0.0;
  double Cdot = 0.0;
  int count = 0;                        // particles touched (1 or 2)
  std::array<int, 2> particle{-1, -1};
  std::array<Vec2, 2> J{Vec2::Zero(), Vec2::Zero()};
  std::array<Vec2, 2> Jdot{Vec2::Zero(), Vec2::Zero()};
};

// Drift feedback (the last two terms of the equation above). C̈ + k_d Ċ + k_s C = 0 is a damped
// oscillator: the defaults k_s = 100 s⁻², k_d = 20 s⁻¹ damp it critically with a 0.1 s time
// constant, fast against the demos' motion and slow against their time steps (h ω ≤ 1.5 at the
// soft body's h = 0.15, inside every integrator's stable region for a real negative eigenvalue).
struct ConstraintFeedback {
  double ks = 100.0;
  double kd = 20.0;
};

// Every constraint kind's keys end with the feedback gains `ks` and `kd` (defaults above).
std::vector<ParamSpec> withFeedbackParams(std::vector<ParamSpec> params);
ConstraintFeedback feedbackFrom(const KindArgs& args);

class Constraint {
 public:
  explicit Constraint(ConstraintFeedback feedback) : feedback_(feedback) {}
  virtual ~Constraint() = default;
  virtual std::string_view kind() const = 0;
  virtual ConstraintRow evaluate(const StateView& s) const = 0;
  // How far the geometry is off, in metres (distance off the wire, off the rod's length, off the
  // line): C itself is not a length for every kind.
  virtual double violation(const StateView& s) const = 0;
  const ConstraintFeedback& feedback() const { return feedback_; }
  // The particles this constraint touches (for validation).
  virtual std::vector<int> particles() const = 0;
  // Adds what this constraint shows (a rod, a wire, a rail) to the frame's drawing.
  virtual void draw(const StateView& s, Drawing& out) const = 0;

 private:
  ConstraintFeedback feedback_;
};

}  // namespace particles
