#include "style/camera_path.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace particles::style {

CameraPath::CameraPath(const ViewStyle& view, const CameraPlacement& fixed, double aspect)
    : view_(view), fixed_(fixed), aspect_(aspect), fitted_(fixed) {
  if (!(aspect > 0.0)) throw std::invalid_argument("the frame's aspect must be positive");
  if (view.mode == ViewStyle::Mode::keys && view.keys.empty()) {
    throw std::invalid_argument("a camera by keys needs at least one key");
  }
  center_ = fixed.center;
}

void CameraPath::observe(const Drawing& f) {
  auto add = [&](const Vec2& p) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return;
    if (boxEmpty_) {
      boxLo_ = boxHi_ = p;
      boxEmpty_ = false;
    } else {
      boxLo_ = boxLo_.cwiseMin(p);
      boxHi_ = boxHi_.cwiseMax(p);
    }
  };
  if (view_.fitAll) {
    for (const Vec2& p : f.particles) add(p);
    for (const Drawing::Box& b : f.bodies) {
      // The rectangle's corners: the whole body stays in view.
      const double c = std::cos(b.angle), s = std::sin(b.angle);
      const Vec2 hx = 0.5 * b.size.x() * Vec2(c, s), hy = 0.5 * b.size.y() * Vec2(-s, c);
      for (const Vec2& corner :
           std::array<Vec2, 4>{b.center - hx - hy, b.center + hx - hy, b.center + hx + hy, b.center - hx + hy}) {
        add(corner);
      }
    }
    return;
  }
  for (int i : view_.fitParticles) {
    if (i >= 0 && size_t(i) < f.particles.size()) add(f.particles[size_t(i)]);
  }
  for (int j : view_.fitBodies) {
    if (j >= 0 && size_t(j) < f.bodies.size()) add(f.bodies[size_t(j)].center);
  }
}

void CameraPath::endPass() {
  if (view_.mode != ViewStyle::Mode::fit || boxEmpty_) return;
  const Vec2 size = boxHi_ - boxLo_;
  // The height that shows the box's height, and its width at the frame's aspect; a point alone
  // keeps the scenario's height.
  double height = std::max(size.y(), size.x() / aspect_);
  height = height > 0.0 ? height * (1.0 + 2.0 * view_.margin) : fixed_.height;
  fitted_ = {0.5 * (boxLo_ + boxHi_), height};
}

Vec2 CameraPath::followedPoint(const System& system) const {
  const StateView s = system.view();
  if (view_.followBody >= 0) return s.pos(system.model().layout.bodyPoint(view_.followBody));
  return s.pos(view_.followParticle);
}

void CameraPath::start(const System& system) {
  if (view_.mode != ViewStyle::Mode::follow) return;
  center_ = followedPoint(system);
  velocity_ = Vec2::Zero();
}

void CameraPath::afterStep(const System& system, double dt) {
  if (view_.mode != ViewStyle::Mode::follow) return;
  const Vec2 target = followedPoint(system);
  if (!(view_.smoothing > 0.0)) {
    center_ = target;
    velocity_ = Vec2::Zero();
    return;
  }
  const double omega = 1.0 / view_.smoothing;
  const double decay = std::exp(-omega * dt);
  const Vec2 e = center_ - target;
  const Vec2 drift = velocity_ + omega * e;
  center_ = target + (e + drift * dt) * decay;
  velocity_ = (velocity_ - omega * drift * dt) * decay;
}

CameraPlacement CameraPath::at(double t) const {
  switch (view_.mode) {
    case ViewStyle::Mode::fixed: return fixed_;
    case ViewStyle::Mode::fit: return fitted_;
    case ViewStyle::Mode::follow: return {center_, fixed_.height};
    case ViewStyle::Mode::keys: break;
  }
  const std::vector<CameraKey>& keys = view_.keys;
  if (t <= keys.front().t) return {keys.front().center, keys.front().height};
  if (t >= keys.back().t) return {keys.back().center, keys.back().height};
  const auto next = std::upper_bound(keys.begin(), keys.end(), t, [](double v, const CameraKey& k) { return v < k.t; });
  const CameraKey& a = *(next - 1);
  const CameraKey& b = *next;
  const double s = (t - a.t) / (b.t - a.t);
  const double eased = s * s * (3.0 - 2.0 * s);
  return {a.center + eased * (b.center - a.center), a.height * std::pow(b.height / a.height, eased)};
}

}  // namespace particles::style
