#pragma once
// A solid obstacle that pushes points out with a penalty force (docs/physics.md §6):
//   f = n k d²   (plus an optional damping −c (v·n) n while in contact; c = 0 as in the report)
// with n the way out and d the penetration depth. The stored energy is U = k d³ / 3.
// Each kind only describes its geometry (contact); collisions.cpp applies the response to
// particles and to the corners of rigid rectangles, where the force also gives a torque.

#include <optional>
#include <string_view>

#include "core/drawing.hpp"
#include "core/kind.hpp"
#include "core/state.hpp"

namespace particles {

struct Contact {
  Vec2 normal;   // unit, pointing out of the obstacle
  double depth;  // m, > 0
};

struct PenaltyParams {
  double k = 1e4;        // N/m², stiffness of f = n k d²
  double damping = 0.0;  // N·s/m along n while in contact
};

// Every collider kind's keys end with the penalty's `k` and `damping` (defaults above).
std::vector<ParamSpec> withPenaltyParams(std::vector<ParamSpec> params);
PenaltyParams penaltyFrom(const KindArgs& args);

class Collider {
 public:
  explicit Collider(PenaltyParams params) : params_(params) {}
  virtual ~Collider() = default;
  virtual std::string_view kind() const = 0;
  // The contact of point p, or nothing when p is on the allowed side.
  virtual std::optional<Contact> contact(const Vec2& p) const = 0;
  // Adds the obstacle's shape to the frame's drawing.
  virtual void draw(Drawing& out) const = 0;
  const PenaltyParams& params() const { return params_; }

 private:
  PenaltyParams params_;
};

}  // namespace particles
