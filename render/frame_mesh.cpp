#include "render/frame_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <stdexcept>
#include <vector>

namespace particles::render {

namespace {

// World to pixels through a camera (render/render_options.hpp's Camera), as every path places shapes.
class PixelMapping {
 public:
  PixelMapping(const Camera& camera, const RenderOptions& options)
      : camera_(camera), width_(options.width), height_(options.height), scale_(pixelsPerUnit(camera, options)) {}
  P2 operator()(const Vec2& p) const {
    return {float(0.5 * width_ + (p.x() - camera_.center.x()) * scale_),
            float(0.5 * height_ - (p.y() - camera_.center.y()) * scale_)};
  }
  double scale() const { return scale_; }  // pixels per world unit

 private:
  const Camera& camera_;
  int width_, height_;
  double scale_;
};

// A look's arrow (FrameLook::Arrow) from pixel `from` to `to`: a shaft `width` wide and a head
// 3 widths wide and long, shortened to the arrow's length (a short arrow is all head). Drawn as
// convex pieces of one outline, as the cursor is: the shaft, and the head cut into three triangles
// at the shaft's sides, so that every edge inside the outline is shared and left unsmoothed. A
// translucent arrow then covers each pixel once, with no seam where shaft and head meet; the head's
// base beside the shaft is outline, smoothed. Always kLookArrowPieces shapes (some degenerate, for
// a zero-length arrow or one without a shaft), so that every arrow takes the same slots.
constexpr size_t kLookArrowPieces = 4;
constexpr float kArrowHeadWidths = 3.0f;
void arrowShapes(ShapeSink& mesh, P2 from, P2 to, float width, Rgba color) {
  const float dx = to[0] - from[0], dy = to[1] - from[1];
  const float length = std::hypot(dx, dy);
  const P2 u = length > 0.0f ? P2{dx / length, dy / length} : P2{0.0f, 0.0f};  // zero: every piece degenerate
  const P2 v = {-u[1], u[0]};
  const float headLength = std::min(kArrowHeadWidths * width, length);
  const bool shaft = length - headLength > 1e-4f;
  const float shaftHalf = 0.5f * width, headHalf = 0.5f * kArrowHeadWidths * width;
  const auto at = [&](P2 p, float along, float across) -> P2 {
    return {p[0] + u[0] * along + v[0] * across, p[1] + u[1] * along + v[1] * across};
  };
  const P2 base = at(to, -headLength, 0.0f);
  const P2 shaftLeft = at(base, 0.0f, shaftHalf), shaftRight = at(base, 0.0f, -shaftHalf);
  // Bit i smooths edge i → i + 1: the shaft's end against the head is shared.
  mesh.convex({at(from, 0.0f, shaftHalf), shaftLeft, shaftRight, at(from, 0.0f, -shaftHalf)}, color, 0b1101);
  mesh.convex({to, at(base, 0.0f, headHalf), shaftLeft}, color, 0b011);
  mesh.convex({to, shaftLeft, shaftRight}, color, shaft ? 0b000 : 0b010);
  mesh.convex({to, shaftRight, at(base, 0.0f, -headHalf)}, color, 0b110);
}

// Throws std::invalid_argument unless `list` (the look's member `name`) is empty or has `count`
// entries, one per `item` of the drawing.
template <typename T>
void checkLength(const std::vector<T>& list, size_t count, const char* name, const char* items) {
  if (list.empty() || list.size() == count) return;
  throw std::invalid_argument(std::string("FrameLook::") + name + " has " + std::to_string(list.size()) +
                              " entries, and the drawing has " + std::to_string(count) + " " + items +
                              " (give one per item, or none)");
}

// The frame's shapes, section by section in drawing order; the long sections (springs, trails,
// particles) by ranges of their items, so that they can be built in pieces. Each item gives a fixed
// number of shapes (counts()), which is what lets the pieces be written into numbered slots.
class FrameShapes {
 public:
  FrameShapes(const Drawing& f, const Camera& camera, const RenderOptions& options, const Palette& colors,
              const FrameLook* look)
      : f_(f), o_(options), c_(colors), look_(look && !look->empty() ? look : nullptr), toPixel_(camera, options) {
    if (f.springTopology && f.springTopology->ends.size() != 2 * f.springTopology->rest.size()) {
      throw std::invalid_argument("the drawing's spring topology has other than two ends per spring");
    }
    if (look_) {
      checkLength(look_->particleColors, f.particles.size(), "particleColors", "particles");
      checkLength(look_->particleRadiiPx, f.particles.size(), "particleRadiiPx", "particles");
      checkLength(look_->springColors, f.springs.size() + f.springsByIndex(), "springColors", "springs");
      checkLength(look_->bodyFills, f.bodies.size(), "bodyFills", "bodies");
      checkLength(look_->bodyOutlines, f.bodies.size(), "bodyOutlines", "bodies");
    }
    w_ = float(options.width);
    h_ = float(options.height);
    scale_ = toPixel_.scale();
    radius_ = particleRadiusPx(camera, options);
  }

  // Shapes per section, in drawing order.
  struct Counts {
    size_t front, springs, rods, bodies, trails, particles, arrows, cursors;
    size_t total() const { return front + springs + rods + bodies + trails + particles + arrows + cursors; }
  };
  static Counts counts(const Drawing& f, const FrameLook* look) {
    constexpr size_t kArrowPieces = 4, kArrowOutline = 7;  // the cursor drawn in cursors()
    return {2 * f.halfPlanes.size() + 2 * f.disks.size() + f.guideCircles.size() + f.guideLines.size(),
            f.springs.size() + f.springsByIndex(),
            f.rods.size(),
            5 * f.bodies.size(),
            look ? look->trails.size() : 0,
            f.particles.size(),
            look ? kLookArrowPieces * look->arrows.size() : 0,
            f.cursors.size() * (1 + kArrowPieces + kArrowOutline)};
  }
  Counts counts() const { return counts(f_, look_); }

  P2 toPixel(const Vec2& p) const { return toPixel_(p); }

  // Colliders, then constraint guides.
  void front(ShapeSink& mesh) const {
    const float w = w_, h = h_;
    const float diagonal = std::hypot(w, h);
    const float lineWidth = float(o_.outlineWidthPx);
    // Colliders: the solid side filled, its boundary outlined. A half-plane is a quad reaching well
    // past the image on every side (GL clips it), built from the boundary's point nearest the origin.
    for (const Drawing::HalfPlane& hp : f_.halfPlanes) {
      const P2 p0 = toPixel(hp.normal * hp.offset);
      const P2 n = {float(hp.normal.x()), float(-hp.normal.y())};  // towards the free side, in pixels
      const P2 t = {-n[1], n[0]};
      const float reach = std::hypot(p0[0] - 0.5f * w, p0[1] - 0.5f * h) + diagonal + 16.0f;
      const P2 a = {p0[0] + t[0] * reach, p0[1] + t[1] * reach};
      const P2 b = {p0[0] - t[0] * reach, p0[1] - t[1] * reach};
      const P2 bIn = {b[0] - n[0] * 2 * reach, b[1] - n[1] * 2 * reach};
      const P2 aIn = {a[0] - n[0] * 2 * reach, a[1] - n[1] * 2 * reach};
      mesh.convex({a, b, bIn, aIn}, c_.colliderFill);
      mesh.line(a, b, lineWidth, c_.colliderOutline);
    }
    for (const Drawing::Disk& d : f_.disks) {
      const P2 p = toPixel(d.center);
      const float r = float(d.radius * scale_);
      mesh.disc(p, r, c_.colliderFill);
      mesh.ring(p, r, lineWidth, c_.colliderOutline);
    }

    // Constraint guides: circles (wires), and lines across the whole view (rails), clipped to the
    // image grown by kGuideOverhangPx.
    for (const Drawing::Circle& circle : f_.guideCircles) {
      mesh.ring(toPixel(circle.center), float(circle.radius * scale_), float(o_.guideWidthPx), c_.guide);
    }
    const float lo = -kGuideOverhangPx;
    for (const Drawing::Line& line : f_.guideLines) {
      const P2 p = toPixel(line.point);
      const double dx = line.direction.x(), dy = -line.direction.y();  // pixel y points down
      if (std::abs(dx) >= std::abs(dy)) {  // mostly horizontal: from the left edge to the right
        const auto yAt = [&](float x) { return float(p[1] + (double(x) - p[0]) * dy / dx); };
        const float hi = w + kGuideOverhangPx;
        mesh.line({lo, yAt(lo)}, {hi, yAt(hi)}, float(o_.guideWidthPx), c_.guide);
      } else {  // mostly vertical: from the top edge to the bottom
        const auto xAt = [&](float y) { return float(p[0] + (double(y) - p[1]) * dx / dy); };
        const float hi = h + kGuideOverhangPx;
        mesh.line({xAt(lo), lo}, {xAt(hi), hi}, float(o_.guideWidthPx), c_.guide);
      }
    }
  }

  // Springs [begin, end) of the section: those by position (Drawing::springs), then those by index
  // (Drawing::springTopology), their ends and strain found as System::draw finds them.
  // The look's colour for spring i of the section, else its strain colour.
  void springs(ShapeSink& mesh, size_t begin, size_t end) const {
    const float width = float(o_.springWidthPx);
    const size_t byPosition = f_.springs.size();
    const bool styled = look_ && !look_->springColors.empty();
    for (size_t i = begin; i < std::min(end, byPosition); ++i) {
      const Drawing::Spring& s = f_.springs[i];
      const Rgba color = styled ? look_->springColors[i] : Rgba(springColor(c_, s.strain, o_.strainForFullColor));
      mesh.line(toPixel(s.a), toPixel(s.b), width, color);
    }
    for (size_t i = std::max(begin, byPosition); i < end; ++i) {
      const Drawing::SpringTopology& topology = *f_.springTopology;
      const size_t k = i - byPosition;
      const Vec2& a = particleAt(topology.ends[2 * k]);
      const Vec2& b = particleAt(topology.ends[2 * k + 1]);
      const double rest = topology.rest[k];
      const double strain = rest > 0.0 ? (a - b).norm() / rest - 1.0 : 0.0;
      const Rgba color = styled ? look_->springColors[i] : Rgba(springColor(c_, strain, o_.strainForFullColor));
      mesh.line(toPixel(a), toPixel(b), width, color);
    }
  }

  void rods(ShapeSink& mesh) const {
    for (const Drawing::Segment& r : f_.rods) mesh.line(toPixel(r.a), toPixel(r.b), float(o_.rodWidthPx), c_.rod);
  }

  void bodies(ShapeSink& mesh) const {
    const bool fills = look_ && !look_->bodyFills.empty(), outlines = look_ && !look_->bodyOutlines.empty();
    for (size_t i = 0; i < f_.bodies.size(); ++i) {
      const Drawing::Box& body = f_.bodies[i];
      const double cs = std::cos(body.angle), sn = std::sin(body.angle);
      const Vec2 hx = 0.5 * body.size.x() * Vec2(cs, sn), hy = 0.5 * body.size.y() * Vec2(-sn, cs);
      const std::array<P2, 4> corners = {toPixel(body.center - hx - hy), toPixel(body.center + hx - hy),
                                         toPixel(body.center + hx + hy), toPixel(body.center - hx + hy)};
      mesh.convex(corners, fills ? look_->bodyFills[i] : Rgba(c_.bodyFill));
      mesh.closedOutline(corners, float(o_.outlineWidthPx), outlines ? look_->bodyOutlines[i] : Rgba(c_.bodyOutline));
    }
  }

  // The look's trail pieces [begin, end), one line each, without caps as springs are.
  void trails(ShapeSink& mesh, size_t begin, size_t end) const {
    for (size_t i = begin; i < end; ++i) {
      const FrameLook::Stroke& piece = look_->trails[i];
      mesh.line(toPixel(piece.a), toPixel(piece.b), piece.widthPx, piece.color);
    }
  }

  void particles(ShapeSink& mesh, size_t begin, size_t end) const {
    const bool colored = look_ && !look_->particleColors.empty(), sized = look_ && !look_->particleRadiiPx.empty();
    for (size_t i = begin; i < end; ++i) {
      const P2 p = toPixel(f_.particles[i]);
      const bool fixed = i < f_.particleFixed.size() && f_.particleFixed[i];
      const Rgba color = colored ? look_->particleColors[i] : Rgba(fixed ? c_.fixedParticle : c_.particle);
      const float radius = sized ? look_->particleRadiiPx[i] : radius_;
      if (fixed) {
        const float s = 0.9f * radius;  // a fixed particle is a square, so it reads as pinned
        mesh.convex({{p[0] - s, p[1] - s}, {p[0] + s, p[1] - s}, {p[0] + s, p[1] + s}, {p[0] - s, p[1] + s}}, color);
      } else {
        mesh.disc(p, radius, color);
      }
    }
  }

  // The look's arrows, kLookArrowPieces shapes each (arrowShapes).
  void arrows(ShapeSink& mesh) const {
    if (!look_) return;
    for (const FrameLook::Arrow& arrow : look_->arrows) {
      arrowShapes(mesh, toPixel(arrow.from), toPixel(arrow.to), arrow.widthPx, arrow.color);
    }
  }

  const Vec2& particleAt(std::uint32_t index) const {
    if (index >= f_.particles.size()) {
      throw std::invalid_argument("a spring of the drawing's topology ends at particle " + std::to_string(index) +
                                  ", and the drawing has " + std::to_string(f_.particles.size()) + " particles");
    }
    return f_.particles[index];
  }

  // The scripted mouse: a line to the grabbed point, then an arrow pointer with its tip on the
  // target (the classic 12 × 20 px shape, pointing up and left).
  void cursors(ShapeSink& mesh) const {
    for (const Drawing::Cursor& mouse : f_.cursors) {
      const P2 tip = toPixel(mouse.target);
      mesh.line(tip, toPixel(mouse.grabbed), float(o_.springWidthPx), c_.mouse);
      auto at = [&](float x, float y) -> P2 { return {tip[0] + x, tip[1] + y}; };
      const std::array<P2, 7> arrow = {at(0, 0),      at(0, 17),       at(4.5f, 13), at(7.5f, 20),
                                       at(10.0f, 19), at(7.0f, 12.2f), at(12, 12.2f)};
      // Convex pieces of the arrow; only edges on its outline are smoothed (bit i: edge i → i + 1).
      mesh.convex({arrow[0], arrow[1], arrow[2]}, c_.mouse, 0b011);
      mesh.convex({arrow[0], arrow[2], arrow[5]}, c_.mouse, 0b000);
      mesh.convex({arrow[0], arrow[5], arrow[6]}, c_.mouse, 0b110);
      mesh.convex({arrow[2], arrow[3], arrow[4], arrow[5]}, c_.mouse, 0b0111);
      mesh.closedOutline(arrow, 1.25f, c_.mouseOutline);
    }
  }

 private:
  const Drawing& f_;
  const RenderOptions& o_;
  const Palette& c_;
  const FrameLook* look_;  // null: the theme's look
  const PixelMapping toPixel_;
  float w_, h_, radius_;
  double scale_;
};

// Items per piece of a long section built on threads: a piece of springs writes 1 MiB of records.
constexpr size_t kShapesPerPiece = 16384;

}  // namespace

void buildFrameMesh(const Drawing& f, const Camera& camera, const RenderOptions& options, const Palette& c,
                    ShapeSink& mesh, const FrameLook* look) {
  const FrameShapes frame(f, camera, options, c, look);
  const FrameShapes::Counts counts = frame.counts();
  mesh.clear();
  frame.front(mesh);
  frame.springs(mesh, 0, counts.springs);
  frame.rods(mesh);
  frame.bodies(mesh);
  frame.trails(mesh, 0, counts.trails);
  frame.particles(mesh, 0, f.particles.size());
  frame.arrows(mesh);
  frame.cursors(mesh);
}

size_t buildFrameTiles(const Drawing& f, const Camera& camera, const RenderOptions& options, const Palette& c,
                       TileBins& bins, WorkerPool* pool, const FrameLook* look) {
  const FrameShapes frame(f, camera, options, c, look);
  const FrameShapes::Counts counts = frame.counts();
  bins.slots(counts.total());
  size_t recorded = 0;
  size_t slot = 0;
  auto serial = [&](auto section, size_t shapes) {
    TileBins::SlotWriter out = bins.writer(slot);
    section(out);
    if (out.next() != slot + shapes) throw std::logic_error("buildFrameTiles: a section gave other than its count of shapes");
    recorded += out.recorded();
    slot += shapes;
  };
  // A long section in pieces of kShapesPerPiece items, each item one shape.
  std::vector<size_t> pieceRecorded;
  auto pieces = [&](auto section, size_t items) {
    pieceRecorded.assign(chunkCount(items, kShapesPerPiece), 0);
    forChunks(pool, items, kShapesPerPiece, [&](size_t begin, size_t end) {
      TileBins::SlotWriter out = bins.writer(slot + begin);
      section(out, begin, end);
      if (out.next() != slot + end) throw std::logic_error("buildFrameTiles: an item gave other than one shape");
      pieceRecorded[begin / kShapesPerPiece] = out.recorded();
    });
    for (size_t n : pieceRecorded) recorded += n;
    slot += items;
  };
  serial([&](ShapeSink& out) { frame.front(out); }, counts.front);
  pieces([&](ShapeSink& out, size_t begin, size_t end) { frame.springs(out, begin, end); }, counts.springs);
  serial([&](ShapeSink& out) { frame.rods(out); }, counts.rods);
  serial([&](ShapeSink& out) { frame.bodies(out); }, counts.bodies);
  pieces([&](ShapeSink& out, size_t begin, size_t end) { frame.trails(out, begin, end); }, counts.trails);
  pieces([&](ShapeSink& out, size_t begin, size_t end) { frame.particles(out, begin, end); }, counts.particles);
  serial([&](ShapeSink& out) { frame.arrows(out); }, counts.arrows);
  serial([&](ShapeSink& out) { frame.cursors(out); }, counts.cursors);
  return recorded;
}

MeshBreaks buildFrameMeshAround(const Drawing& f, const Camera& camera, const RenderOptions& options, const Palette& c,
                                ShapeMesh& mesh, const FrameLook* look) {
  const FrameShapes frame(f, camera, options, c, look);
  mesh.clear();
  frame.front(mesh);
  frame.springs(mesh, 0, f.springs.size());  // by position only: the resident path draws the others
  MeshBreaks breaks;
  breaks.springsEnd = mesh.vertices().size();
  frame.rods(mesh);
  frame.bodies(mesh);
  frame.trails(mesh, 0, frame.counts().trails);
  breaks.particlesAt = mesh.vertices().size();
  frame.arrows(mesh);
  frame.cursors(mesh);
  return breaks;
}

void particlePixels(const Drawing& f, const Camera& camera, const RenderOptions& options, std::vector<float>& pixels,
                    WorkerPool* pool) {
  const PixelMapping toPixel(camera, options);
  pixels.resize(2 * f.particles.size());
  forChunks(pool, f.particles.size(), kShapesPerPiece, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const P2 p = toPixel(f.particles[i]);
      pixels[2 * i] = p[0];
      pixels[2 * i + 1] = p[1];
    }
  });
}

double pixelsPerUnit(const Camera& camera, const RenderOptions& options) {
  if (!(camera.height > 0.0)) throw std::invalid_argument("camera height must be positive");
  return double(options.height) / camera.height;
}

float particleRadiusPx(const Camera& camera, const RenderOptions& options) {
  return float(options.particleRadius.unit == Length::Unit::world
                   ? options.particleRadius.value * pixelsPerUnit(camera, options)
                   : options.particleRadius.value);
}

size_t frameShapeCount(const Drawing& f, const FrameLook* look) {
  return FrameShapes::counts(f, look).total();
}

}  // namespace particles::render
