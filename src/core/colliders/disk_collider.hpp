#pragma once
// Solid disk {c, r}: a point with |p − c| < r is inside, leaves along n = (p − c)/|p − c| and has
// depth r − |p − c| (docs/physics.md §6). At the exact centre the way out is taken as +y.

#include "core/collider.hpp"

namespace particles {

class DiskCollider final : public Collider {
 public:
  DiskCollider(const Vec2& center, double radius, PenaltyParams params = {})
      : Collider(params), center_(center), radius_(radius) {}
  const Vec2& center() const { return center_; }
  double radius() const { return radius_; }

  std::string_view kind() const override { return "disk"; }
  void draw(Drawing& out) const override { out.disks.push_back({center_, radius_}); }
  std::optional<Contact> contact(const Vec2& p) const override {
    const Vec2 d = p - center_;
    const double dist = d.norm();
    if (dist >= radius_) return std::nullopt;
    const Vec2 n = dist > 0.0 ? Vec2(d / dist) : Vec2(0.0, 1.0);
    return Contact{n, radius_ - dist};
  }

 private:
  Vec2 center_;
  double radius_;
};

// How scenario files write it (`{type: disk, center, radius, k, damping}`).
const KindSpec& diskKind();

}  // namespace particles
