#pragma once
// Half-plane {n, d₀}: the allowed side is n·p ≥ d₀ (n is normalised on construction), so the
// solid fills n·p < d₀ and a point there has depth d = d₀ − n·p and leaves along n (docs/physics.md §6).
// The ground y = −1.5 is {normal [0, 1], offset −1.5}.

#include "core/collider.hpp"

namespace particles {

class HalfPlaneCollider final : public Collider {
 public:
  HalfPlaneCollider(const Vec2& normal, double offset, PenaltyParams params = {})
      : Collider(params), normal_(normal.normalized()), offset_(offset) {}
  const Vec2& normal() const { return normal_; }
  double offset() const { return offset_; }

  std::string_view kind() const override { return "half_plane"; }
  void draw(Drawing& out) const override { out.halfPlanes.push_back({normal_, offset_}); }
  std::optional<Contact> contact(const Vec2& p) const override {
    const double depth = offset_ - normal_.dot(p);
    if (depth <= 0.0) return std::nullopt;
    return Contact{normal_, depth};
  }

 private:
  Vec2 normal_;
  double offset_;
};

// How scenario files write it (`{type: half_plane, normal, offset, k, damping}`).
const KindSpec& halfPlaneKind();

}  // namespace particles
