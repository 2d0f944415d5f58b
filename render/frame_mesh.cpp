#include "render/frame_mesh.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace particles::render {

void buildFrameMesh(const Drawing& f, const Camera& camera, const RenderOptions& options, const Theme& c,
                    ShapeSink& mesh) {
  if (!(camera.height > 0.0)) throw std::invalid_argument("camera height must be positive");
  const float w = float(options.width), h = float(options.height);
  const double scale = double(options.height) / camera.height;  // pixels per world unit
  auto toPixel = [&](const Vec2& p) -> P2 {
    return {float(0.5 * options.width + (p.x() - camera.center.x()) * scale),
            float(0.5 * options.height - (p.y() - camera.center.y()) * scale)};
  };
  const float diagonal = std::hypot(w, h);
  const float lineWidth = float(options.outlineWidthPx);
  mesh.clear();

  // Colliders: the solid side filled, its boundary outlined. A half-plane is a quad reaching well
  // past the image on every side (GL clips it), built from the boundary's point nearest the origin.
  for (const Drawing::HalfPlane& hp : f.halfPlanes) {
    const P2 p0 = toPixel(hp.normal * hp.offset);
    const P2 n = {float(hp.normal.x()), float(-hp.normal.y())};  // towards the free side, in pixels
    const P2 t = {-n[1], n[0]};
    const float reach = std::hypot(p0[0] - 0.5f * w, p0[1] - 0.5f * h) + diagonal + 16.0f;
    const P2 a = {p0[0] + t[0] * reach, p0[1] + t[1] * reach};
    const P2 b = {p0[0] - t[0] * reach, p0[1] - t[1] * reach};
    const P2 bIn = {b[0] - n[0] * 2 * reach, b[1] - n[1] * 2 * reach};
    const P2 aIn = {a[0] - n[0] * 2 * reach, a[1] - n[1] * 2 * reach};
    mesh.convex({a, b, bIn, aIn}, c.colliderFill);
    mesh.line(a, b, lineWidth, c.colliderOutline);
  }
  for (const Drawing::Disk& d : f.disks) {
    const P2 p = toPixel(d.center);
    const float r = float(d.radius * scale);
    mesh.disc(p, r, c.colliderFill);
    mesh.ring(p, r, lineWidth, c.colliderOutline);
  }

  // Constraint guides: circles (wires), and lines across the whole view (rails), clipped to the
  // image grown by kGuideOverhangPx.
  for (const Drawing::Circle& circle : f.guideCircles) {
    mesh.ring(toPixel(circle.center), float(circle.radius * scale), float(options.guideWidthPx), c.guide);
  }
  const float lo = -kGuideOverhangPx;
  for (const Drawing::Line& line : f.guideLines) {
    const P2 p = toPixel(line.point);
    const double dx = line.direction.x(), dy = -line.direction.y();  // pixel y points down
    if (std::abs(dx) >= std::abs(dy)) {  // mostly horizontal: from the left edge to the right
      const auto yAt = [&](float x) { return float(p[1] + (double(x) - p[0]) * dy / dx); };
      const float hi = w + kGuideOverhangPx;
      mesh.line({lo, yAt(lo)}, {hi, yAt(hi)}, float(options.guideWidthPx), c.guide);
    } else {  // mostly vertical: from the top edge to the bottom
      const auto xAt = [&](float y) { return float(p[0] + (double(y) - p[1]) * dx / dy); };
      const float hi = h + kGuideOverhangPx;
      mesh.line({xAt(lo), lo}, {xAt(hi), hi}, float(options.guideWidthPx), c.guide);
    }
  }

  for (const Drawing::Spring& s : f.springs) {
    mesh.line(toPixel(s.a), toPixel(s.b), float(options.springWidthPx),
              springColor(c, s.strain, options.strainForFullColor));
  }
  for (const Drawing::Segment& r : f.rods) mesh.line(toPixel(r.a), toPixel(r.b), float(options.rodWidthPx), c.rod);

  for (const Drawing::Box& body : f.bodies) {
    const double cs = std::cos(body.angle), sn = std::sin(body.angle);
    const Vec2 hx = 0.5 * body.size.x() * Vec2(cs, sn), hy = 0.5 * body.size.y() * Vec2(-sn, cs);
    const std::vector<P2> corners = {toPixel(body.center - hx - hy), toPixel(body.center + hx - hy),
                                     toPixel(body.center + hx + hy), toPixel(body.center - hx + hy)};
    mesh.convex(corners, c.bodyFill);
    mesh.closedOutline(corners, lineWidth, c.bodyOutline);
  }

  const float radius = float(options.particleRadius.unit == Length::Unit::world ? options.particleRadius.value * scale
                                                                                : options.particleRadius.value);
  for (size_t i = 0; i < f.particles.size(); ++i) {
    const P2 p = toPixel(f.particles[i]);
    if (i < f.particleFixed.size() && f.particleFixed[i]) {
      const float s = 0.9f * radius;  // a fixed particle is a square, so it reads as pinned
      mesh.convex({{p[0] - s, p[1] - s}, {p[0] + s, p[1] - s}, {p[0] + s, p[1] + s}, {p[0] - s, p[1] + s}},
                  c.fixedParticle);
    } else {
      mesh.disc(p, radius, c.particle);
    }
  }

  // The scripted mouse: a line to the grabbed point, then an arrow pointer with its tip on the
  // target (the classic 12 × 20 px shape, pointing up and left).
  for (const Drawing::Cursor& mouse : f.cursors) {
    const P2 tip = toPixel(mouse.target);
    mesh.line(tip, toPixel(mouse.grabbed), float(options.springWidthPx), c.mouse);
    auto at = [&](float x, float y) -> P2 { return {tip[0] + x, tip[1] + y}; };
    const std::vector<P2> arrow = {at(0, 0),      at(0, 17),       at(4.5f, 13), at(7.5f, 20),
                                   at(10.0f, 19), at(7.0f, 12.2f), at(12, 12.2f)};
    // Convex pieces of the arrow; only edges on its outline are smoothed (bit i: edge i → i + 1).
    mesh.convex({arrow[0], arrow[1], arrow[2]}, c.mouse, 0b011);
    mesh.convex({arrow[0], arrow[2], arrow[5]}, c.mouse, 0b000);
    mesh.convex({arrow[0], arrow[5], arrow[6]}, c.mouse, 0b110);
    mesh.convex({arrow[2], arrow[3], arrow[4], arrow[5]}, c.mouse, 0b0111);
    mesh.closedOutline(arrow, 1.25f, c.mouseOutline);
  }
}

size_t frameShapeCount(const Drawing& f) {
  constexpr size_t kArrowPieces = 4, kArrowOutline = 7;  // the cursor drawn above
  return 2 * f.halfPlanes.size() + 2 * f.disks.size() + f.guideCircles.size() + f.guideLines.size() +
         f.springs.size() + f.rods.size() + 5 * f.bodies.size() + f.particles.size() +
         f.cursors.size() * (1 + kArrowPieces + kArrowOutline);
}

}  // namespace particles::render
