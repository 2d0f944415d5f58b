#include "render/shape_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace particles::render {

namespace {

ShapeVertex vertex(P2 p, Rgba col, float kind) {
  return {p[0], p[1], {0, 0, 0, 0}, kind, {col.r, col.g, col.b, col.a}};
}

}  // namespace

ConvexEdges convexEdges(std::span<const P2> corners, unsigned smoothEdges) {
  ConvexEdges e;
  const size_t n = corners.size();
  if (n < 3 || n > 4) throw std::logic_error("a convex shape takes 3 or 4 corners");
  e.count = n;
  float cx = 0, cy = 0;
  for (const P2& p : corners) cx += p[0] / float(n), cy += p[1] / float(n);
  for (size_t i = 0; i < n; ++i) {
    const P2 a = corners[i], b = corners[(i + 1) % n];
    const float len = std::hypot(b[0] - a[0], b[1] - a[1]);
    if (!(len > 1e-4f)) return e;  // degenerate: nothing to draw
    P2 m = {-(b[1] - a[1]) / len, (b[0] - a[0]) / len};
    if (m[0] * (cx - a[0]) + m[1] * (cy - a[1]) < 0) m = {-m[0], -m[1]};
    e.normal[i] = m;
    e.push[i] = (smoothEdges >> i & 1u) ? kFringePx : 0.0f;
  }
  // Corner i of the grown polygon: where edges i − 1 and i, each moved out by its push, meet.
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + n - 1) % n;
    const P2 p = corners[i], u = e.normal[j], v = e.normal[i];
    const float det = u[0] * v[1] - u[1] * v[0];
    if (std::abs(det) < 1e-6f) {  // the two edges are parallel
      e.grown[i] = {p[0] - v[0] * e.push[i], p[1] - v[1] * e.push[i]};
    } else {  // solve u·(q − p) = −push[j], v·(q − p) = −push[i]
      const float rj = -e.push[j], ri = -e.push[i];
      e.grown[i] = {p[0] + (rj * v[1] - ri * u[1]) / det, p[1] + (ri * u[0] - rj * v[0]) / det};
    }
  }
  e.valid = true;
  return e;
}

void ShapeMesh::convex(std::span<const P2> corners, Rgba col, unsigned smoothEdges) {
  const ConvexEdges e = convexEdges(corners, smoothEdges);
  if (!e.valid) return;
  const size_t n = e.count;
  std::array<ShapeVertex, 4> grown{};
  for (size_t i = 0; i < n; ++i) {
    const P2 q = e.grown[i];
    ShapeVertex& out = grown[i];
    out = vertex(q, col, 0.0f);
    for (size_t k = 0; k < 4; ++k) {
      const bool tested = k < n && (smoothEdges >> k & 1u);
      out.shape[k] = tested ? e.normal[k][0] * (q[0] - corners[k][0]) + e.normal[k][1] * (q[1] - corners[k][1]) : kFarPx;
    }
  }
  for (size_t i = 1; i + 1 < n; ++i) {
    vertices_.push_back(grown[0]);
    vertices_.push_back(grown[i]);
    vertices_.push_back(grown[i + 1]);
  }
}

void ShapeSink::line(P2 a, P2 b, float width, Rgba col, bool squareCaps) {
  float dx = b[0] - a[0], dy = b[1] - a[1];
  const float len = std::hypot(dx, dy);
  if (!(len > 1e-4f)) return;
  dx /= len;
  dy /= len;
  const float h = 0.5f * width;
  const float nx = -dy * h, ny = dx * h;
  if (squareCaps) {
    a = {a[0] - dx * h, a[1] - dy * h};
    b = {b[0] + dx * h, b[1] + dy * h};
  }
  convex({{a[0] + nx, a[1] + ny}, {b[0] + nx, b[1] + ny}, {b[0] - nx, b[1] - ny}, {a[0] - nx, a[1] - ny}}, col);
}

void ShapeSink::closedOutline(std::span<const P2> pts, float width, Rgba col) {
  for (size_t i = 0; i < pts.size(); ++i) line(pts[i], pts[(i + 1) % pts.size()], width, col, true);
}

void ShapeSink::ring(P2 c, float r, float width, Rgba col) {
  annulus(c, std::max(0.0f, r - 0.5f * width), r + 0.5f * width, col);
}

// Covered by a band of quads (a fan when inner is 0) whose polygons contain the annulus grown by
// kFringePx on both sides: the outer polygon is circumscribed, the inner one inscribed. A small
// disc is one square instead, two triangles rather than a fan of eight: llvmpipe's cost is per
// triangle more than per pixel at that size (a particle of the cloth is ~6 px across), and the
// shader decides coverage from the distance to the centre whatever the triangles.
void ShapeMesh::annulus(P2 c, float inner, float outer, Rgba col) {
  const float fringeOuter = outer + kFringePx;
  const float fringeInner = std::max(0.0f, inner - kFringePx);
  const int n = std::clamp(int(std::ceil(2.0f * std::numbers::pi_v<float> * fringeOuter / 16.0f)), 8, 256);
  if (inner <= 0.0f && n == 8) {
    auto corner = [&](float dx, float dy) {
      ShapeVertex v = vertex({c[0] + dx, c[1] + dy}, col, 1.0f);
      v.shape[0] = dx;
      v.shape[1] = dy;
      v.shape[2] = outer;
      v.shape[3] = inner;
      return v;
    };
    const float r = fringeOuter;
    const ShapeVertex a = corner(-r, -r), b = corner(r, -r), d = corner(r, r), e = corner(-r, r);
    vertices_.insert(vertices_.end(), {a, b, d, a, d, e});
    return;
  }
  const float polyOuter = fringeOuter / std::cos(std::numbers::pi_v<float> / float(n));
  auto at = [&](float radius, int i) {
    const double a = 2.0 * std::numbers::pi * double(i % n) / double(n);
    const P2 p = {c[0] + radius * float(std::cos(a)), c[1] + radius * float(std::sin(a))};
    ShapeVertex v = vertex(p, col, 1.0f);
    v.shape[0] = p[0] - c[0];
    v.shape[1] = p[1] - c[1];
    v.shape[2] = outer;
    v.shape[3] = inner;
    return v;
  };
  for (int i = 0; i < n; ++i) {
    const ShapeVertex o0 = at(polyOuter, i), o1 = at(polyOuter, i + 1);
    if (fringeInner > 0.0f) {
      const ShapeVertex i0 = at(fringeInner, i), i1 = at(fringeInner, i + 1);
      vertices_.insert(vertices_.end(), {i0, o0, o1, i0, o1, i1});
    } else {
      vertices_.insert(vertices_.end(), {at(0.0f, 0), o0, o1});
    }
  }
}

}  // namespace particles::render
