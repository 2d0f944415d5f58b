#include "render/renderer.hpp"

#include "render/errors.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
// osmesa.h brings in GL/gl.h; libOSMesa exports the GL 3 entry points (framebuffer objects) too.
#include <GL/glext.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace particles::render {

Theme theme(ThemeName name) {
  if (name == ThemeName::light) {
    return {
        .background = {255, 255, 255},
        .particle = {25, 25, 30},
        .fixedParticle = {200, 110, 0},
        .springCompressed = {30, 90, 220},
        .springRest = {140, 140, 145},
        .springStretched = {215, 35, 30},
        .rod = {40, 40, 45},
        .guide = {0, 135, 75},
        .bodyFill = {175, 198, 232},
        .bodyOutline = {30, 60, 115},
        .colliderFill = {218, 220, 226},
        .colliderOutline = {110, 115, 128},
        .mouse = {250, 170, 0},
        .mouseOutline = {0, 0, 0},
    };
  }
  return {
      .background = {18, 20, 24},
      .particle = {235, 235, 235},
      .fixedParticle = {255, 190, 50},
      .springCompressed = {70, 145, 255},
      .springRest = {135, 138, 145},
      .springStretched = {255, 75, 55},
      .rod = {225, 225, 230},
      .guide = {90, 200, 130},
      .bodyFill = {55, 85, 135},
      .bodyOutline = {175, 205, 245},
      .colliderFill = {44, 48, 56},
      .colliderOutline = {115, 124, 140},
      .mouse = {255, 215, 0},
      .mouseOutline = {0, 0, 0},
  };
}

void validate(const RenderOptions& o) {
  // 16384: OSMesa's largest buffer (OSMESA_MAX_WIDTH/HEIGHT) in Mesa 22.
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384) {
    throw std::invalid_argument("image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                                " is out of range (1 to 16384 pixels per side)");
  }
  if (o.msaa < 1 || o.msaa > 64) {
    throw std::invalid_argument("msaa " + std::to_string(o.msaa) + " is out of range (1 turns it off)");
  }
  if (!(o.particleRadius.value > 0.0)) throw std::invalid_argument("particle radius must be positive");
  if (!(o.springWidthPx > 0.0) || !(o.rodWidthPx > 0.0) || !(o.guideWidthPx > 0.0) || !(o.outlineWidthPx > 0.0)) {
    throw std::invalid_argument("line widths must be positive");
  }
  if (!(o.strainForFullColor > 0.0)) throw std::invalid_argument("strainForFullColor must be positive");
}

namespace {

struct OsMesaContextDeleter {
  void operator()(OSMesaContext c) const { OSMesaDestroyContext(c); }
};
using OsMesaContextPtr = std::unique_ptr<std::remove_pointer_t<OSMesaContext>, OsMesaContextDeleter>;

std::string hex(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04x", v);
  return buf;
}

std::string glErrorName(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    default: return hex(e);
  }
}

void checkGl(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) throw RenderError(std::string(what) + ": OpenGL error " + glErrorName(e));
}

using P2 = std::array<float, 2>;  // a point in pixels, x right, y down from the top-left corner

// Triangles with per-vertex colour, in pixel coordinates; drawn in the order they are added.
class Mesh {
 public:
  void clear() {
    xy_.clear();
    rgba_.clear();
  }
  const std::vector<float>& xy() const { return xy_; }
  const std::vector<std::uint8_t>& rgba() const { return rgba_; }
  GLsizei vertexCount() const { return GLsizei(xy_.size() / 2); }

  void triangle(P2 a, P2 b, P2 c, Rgb col) {
    vertex(a, col);
    vertex(b, col);
    vertex(c, col);
  }
  void quad(P2 a, P2 b, P2 c, P2 d, Rgb col) {  // a b c d around the quad
    triangle(a, b, c, col);
    triangle(a, c, d, col);
  }
  // A segment of the given pixel width; squareCaps extends it by half the width at both ends.
  void line(P2 a, P2 b, float width, Rgb col, bool squareCaps = false) {
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
    quad({a[0] + nx, a[1] + ny}, {b[0] + nx, b[1] + ny}, {b[0] - nx, b[1] - ny}, {a[0] - nx, a[1] - ny}, col);
  }
  void closedOutline(const std::vector<P2>& pts, float width, Rgb col) {
    for (size_t i = 0; i < pts.size(); ++i) line(pts[i], pts[(i + 1) % pts.size()], width, col, true);
  }
  void convexPolygon(const std::vector<P2>& pts, Rgb col) {
    for (size_t i = 1; i + 1 < pts.size(); ++i) triangle(pts[0], pts[i], pts[i + 1], col);
  }
  void disc(P2 c, float r, Rgb col) {
    const int n = segments(r, 1.5f, 8, 128);
    P2 prev = {c[0] + r, c[1]};
    for (int i = 1; i <= n; ++i) {
      const P2 p = onCircle(c, r, i, n);
      triangle(c, prev, p, col);
      prev = p;
    }
  }
  void ring(P2 c, float r, float width, Rgb col) {
    const int n = segments(r, 3.0f, 16, 256);
    const float ri = std::max(0.0f, r - 0.5f * width), ro = r + 0.5f * width;
    for (int i = 0; i < n; ++i) {
      quad(onCircle(c, ri, i, n), onCircle(c, ro, i, n), onCircle(c, ro, i + 1, n), onCircle(c, ri, i + 1, n), col);
    }
  }

 private:
  // Enough segments that each is about `step` pixels long: the polygon then strays from the true
  // circle by r(1 − cos(π/n)), well under a pixel at these steps.
  static int segments(float r, float step, int lo, int hi) {
    return std::clamp(int(std::ceil(2.0f * std::numbers::pi_v<float> * r / step)), lo, hi);
  }
  static P2 onCircle(P2 c, float r, int i, int n) {
    const double a = 2.0 * std::numbers::pi * double(i % n) / double(n);
    return {c[0] + r * float(std::cos(a)), c[1] + r * float(std::sin(a))};
  }
  void vertex(P2 p, Rgb col) {
    xy_.push_back(p[0]);
    xy_.push_back(p[1]);
    rgba_.insert(rgba_.end(), {col.r, col.g, col.b, 255});
  }

  std::vector<float> xy_;
  std::vector<std::uint8_t> rgba_;
};

Rgb mix(Rgb a, Rgb b, double t) {
  auto m = [t](unsigned char x, unsigned char y) {
    return static_cast<unsigned char>(std::lround(double(x) + (double(y) - double(x)) * t));
  };
  return {m(a.r, b.r), m(a.g, b.g), m(a.b, b.b)};
}

}  // namespace

struct Renderer::Impl {
  RenderOptions options;
  Theme colors;
  Image image;  // OSMesa's colour buffer: GL window row y is image row y (see toPixel)
  OsMesaContextPtr context;
  GLuint fbo = 0, colorBuffer = 0;  // the multisampled target, when msaa > 1
  int samples = 1;
  Mesh mesh;

  void makeCurrent() {
    if (!OSMesaMakeCurrent(context.get(), image.rgba.data(), GL_UNSIGNED_BYTE, image.width, image.height)) {
      throw RenderError("OSMesaMakeCurrent(" + std::to_string(image.width) + "x" + std::to_string(image.height) +
                        ", GL_UNSIGNED_BYTE) failed");
    }
  }
  void buildMesh(const FrameSnapshot& frame, const Camera& camera);
};

Renderer::Renderer(const RenderOptions& options) : impl_(std::make_unique<Impl>()) {
  validate(options);
  Impl& m = *impl_;
  m.options = options;
  m.colors = theme(options.themeName);
  m.image = Image(options.width, options.height);

  // No depth, stencil or accumulation buffers: shapes are drawn opaque in painter's order.
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_ACCUM_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_COMPAT_PROFILE,
                         0};
  m.context.reset(OSMesaCreateContextAttribs(attribs, nullptr));
  if (!m.context) {
    throw RenderError(
        "OSMesaCreateContextAttribs(OSMESA_RGBA, compatibility profile) failed: Mesa could not make an off-screen "
        "OpenGL context (is libOSMesa's software rasteriser, llvmpipe or softpipe, installed?)");
  }
  m.makeCurrent();
  // Image row 0 must be the top of the picture: with OSMESA_Y_UP = 1 (the default) memory row 0 is
  // GL window row 0, and toPixel() puts the top of the view there.
  OSMesaPixelStore(OSMESA_Y_UP, 1);

  if (options.msaa > 1) {
    GLint maxSamples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    checkGl("glGetIntegerv(GL_MAX_SAMPLES)");
    if (options.msaa > maxSamples) {
      throw RenderError("msaa " + std::to_string(options.msaa) + " is more than this OpenGL (" +
                        reinterpret_cast<const char*>(glGetString(GL_RENDERER)) +
                        ") supports: GL_MAX_SAMPLES = " + std::to_string(maxSamples));
    }
    glGenFramebuffers(1, &m.fbo);
    glGenRenderbuffers(1, &m.colorBuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, m.colorBuffer);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, options.msaa, GL_RGBA8, options.width, options.height);
    checkGl("glRenderbufferStorageMultisample");
    glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m.colorBuffer);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      throw RenderError("glCheckFramebufferStatus: multisampled framebuffer (" + std::to_string(options.msaa) +
                        " samples) is incomplete, status " + hex(status));
    }
    GLint samples = 0;
    glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &samples);
    checkGl("multisampled framebuffer setup");
    m.samples = samples;
  }
}

Renderer::~Renderer() {
  if (!impl_ || !impl_->context) return;
  if (impl_->fbo != 0 && OSMesaMakeCurrent(impl_->context.get(), impl_->image.rgba.data(), GL_UNSIGNED_BYTE,
                                           impl_->image.width, impl_->image.height)) {
    glDeleteFramebuffers(1, &impl_->fbo);
    glDeleteRenderbuffers(1, &impl_->colorBuffer);
  }
}

const RenderOptions& Renderer::options() const {
  return impl_->options;
}
int Renderer::samples() const {
  return impl_->samples;
}

void Renderer::Impl::buildMesh(const FrameSnapshot& f, const Camera& camera) {
  const Theme& c = colors;
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
  for (const HalfPlaneShape& hp : f.halfPlanes) {
    const P2 p0 = toPixel(hp.normal * hp.offset);
    const P2 n = {float(hp.normal.x()), float(-hp.normal.y())};  // towards the free side, in pixels
    const P2 t = {-n[1], n[0]};
    const float reach = std::hypot(p0[0] - 0.5f * w, p0[1] - 0.5f * h) + diagonal + 16.0f;
    const P2 a = {p0[0] + t[0] * reach, p0[1] + t[1] * reach};
    const P2 b = {p0[0] - t[0] * reach, p0[1] - t[1] * reach};
    const P2 bIn = {b[0] - n[0] * 2 * reach, b[1] - n[1] * 2 * reach};
    const P2 aIn = {a[0] - n[0] * 2 * reach, a[1] - n[1] * 2 * reach};
    mesh.quad(a, b, bIn, aIn, c.colliderFill);
    mesh.line(a, b, lineWidth, c.colliderOutline);
  }
  for (const DiskShape& d : f.disks) {
    const P2 p = toPixel(d.center);
    const float r = float(d.radius * scale);
    mesh.disc(p, r, c.colliderFill);
    mesh.ring(p, r, lineWidth, c.colliderOutline);
  }

  // Constraint guides: wires as circles, rails across the whole width.
  for (const WireCircle& wire : f.wires) {
    mesh.ring(toPixel(wire.center), float(wire.radius * scale), float(options.guideWidthPx), c.guide);
  }
  for (const Rail& rail : f.rails) {
    const float y = toPixel(Vec2(camera.center.x(), rail.height))[1];
    mesh.line({-8.0f, y}, {w + 8.0f, y}, float(options.guideWidthPx), c.guide);
  }

  for (const SpringSegment& s : f.springs) {
    const double t = std::clamp(s.strain / options.strainForFullColor, -1.0, 1.0);
    const Rgb col = t < 0 ? mix(c.springRest, c.springCompressed, -t) : mix(c.springRest, c.springStretched, t);
    mesh.line(toPixel(s.a), toPixel(s.b), float(options.springWidthPx), col);
  }
  for (const RodSegment& r : f.rods) mesh.line(toPixel(r.a), toPixel(r.b), float(options.rodWidthPx), c.rod);

  for (const BodyBox& body : f.bodies) {
    const double cs = std::cos(body.angle), sn = std::sin(body.angle);
    const Vec2 hx = 0.5 * body.size.x() * Vec2(cs, sn), hy = 0.5 * body.size.y() * Vec2(-sn, cs);
    const std::vector<P2> corners = {toPixel(body.center - hx - hy), toPixel(body.center + hx - hy),
                                     toPixel(body.center + hx + hy), toPixel(body.center - hx + hy)};
    mesh.convexPolygon(corners, c.bodyFill);
    mesh.closedOutline(corners, lineWidth, c.bodyOutline);
  }

  const float radius = float(options.particleRadius.unit == Length::Unit::world ? options.particleRadius.value * scale
                                                                                : options.particleRadius.value);
  for (size_t i = 0; i < f.particles.size(); ++i) {
    const P2 p = toPixel(f.particles[i]);
    if (i < f.particleFixed.size() && f.particleFixed[i]) {
      const float s = 0.9f * radius;  // a fixed particle is a square, so it reads as pinned
      mesh.quad({p[0] - s, p[1] - s}, {p[0] + s, p[1] - s}, {p[0] + s, p[1] + s}, {p[0] - s, p[1] + s},
                c.fixedParticle);
    } else {
      mesh.disc(p, radius, c.particle);
    }
  }

  // The scripted mouse: a line to the grabbed point, then an arrow pointer with its tip on the
  // target (the classic 12 × 20 px shape, pointing up and left).
  for (const MouseCursor& mouse : f.mice) {
    const P2 tip = toPixel(mouse.target);
    mesh.line(tip, toPixel(mouse.grabbed), float(options.springWidthPx), c.mouse);
    auto at = [&](float x, float y) -> P2 { return {tip[0] + x, tip[1] + y}; };
    const std::vector<P2> arrow = {at(0, 0),      at(0, 17),       at(4.5f, 13), at(7.5f, 20),
                                   at(10.0f, 19), at(7.0f, 12.2f), at(12, 12.2f)};
    mesh.triangle(arrow[0], arrow[1], arrow[2], c.mouse);
    mesh.triangle(arrow[0], arrow[2], arrow[5], c.mouse);
    mesh.triangle(arrow[0], arrow[5], arrow[6], c.mouse);
    mesh.quad(arrow[2], arrow[3], arrow[4], arrow[5], c.mouse);
    mesh.closedOutline(arrow, 1.25f, c.mouseOutline);
  }
}

const Image& Renderer::render(const FrameSnapshot& frame, const Camera& camera) {
  if (!(camera.height > 0.0)) throw std::invalid_argument("camera height must be positive");
  Impl& m = *impl_;
  m.makeCurrent();
  m.buildMesh(frame, camera);

  const int w = m.options.width, h = m.options.height;
  glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);  // 0: OSMesa's buffer itself
  glViewport(0, 0, w, h);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0.0, double(w), 0.0, double(h), -1.0, 1.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DITHER);
  if (m.fbo != 0) glEnable(GL_MULTISAMPLE);

  const Rgb bg = m.colors.background;
  glClearColor(float(bg.r) / 255.0f, float(bg.g) / 255.0f, float(bg.b) / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);

  if (m.mesh.vertexCount() > 0) {
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(2, GL_FLOAT, 0, m.mesh.xy().data());
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, m.mesh.rgba().data());
    glDrawArrays(GL_TRIANGLES, 0, m.mesh.vertexCount());
    glDisableClientState(GL_COLOR_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
  }
  checkGl("drawing the frame");

  if (m.fbo != 0) {  // resolve the samples into OSMesa's buffer
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m.fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    checkGl("glBlitFramebuffer (multisample resolve)");
  }
  glFinish();
  checkGl("glFinish");
  return m.image;
}

}  // namespace particles::render
