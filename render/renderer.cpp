#include "render/renderer.hpp"

#include "render/errors.hpp"
#include "render/shape_mesh.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
// osmesa.h brings in GL/gl.h; libOSMesa exports the GL 3 entry points (framebuffer objects) too.
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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
  if (std::find(kSampleCounts.begin(), kSampleCounts.end(), o.msaa) == kSampleCounts.end()) {
    throw std::invalid_argument("msaa " + std::to_string(o.msaa) + " is not one of 1 (off), 2, 4, 8, 16");
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

Rgb mix(Rgb a, Rgb b, double t) {
  auto m = [t](unsigned char x, unsigned char y) {
    return static_cast<unsigned char>(std::lround(double(x) + (double(y) - double(x)) * t));
  };
  return {m(a.r, b.r), m(a.g, b.g), m(a.b, b.b)};
}

// Coverage is computed per sample in the fragment shader: each primitive knows its true boundary
// (see ShapeVertex), the pixel's samples sit at the standard positions (samplePattern), and the share
// covered becomes the fragment's alpha, blended over what is already drawn. For one edge over a
// background this is exactly what a multisampled framebuffer resolves to.
constexpr const char* kVertexShader = R"(#version 130
uniform vec2 imageSize;
in vec2 position;   // pixels, x right, y = image row (GL window row, see OSMESA_Y_UP)
in vec4 color;
in vec4 shape;
in float kind;
out vec4 vColor;
out vec4 vShape;
flat out float vKind;
void main() {
  gl_Position = vec4(2.0 * position / imageSize - 1.0, 0.0, 1.0);
  vColor = color;
  vShape = shape;
  vKind = kind;
}
)";

// Compiled once per sample count (SAMPLE_COUNT and SAMPLES are defined before this text) so the
// loop unrolls and llvmpipe's vectorised code has no branches: both shape kinds are evaluated and
// one is selected.
constexpr const char* kFragmentShader = R"(
in vec4 vColor;
in vec4 vShape;
flat in float vKind;
void main() {
  const vec2 samples[SAMPLE_COUNT] = vec2[SAMPLE_COUNT](SAMPLES);
  vec4 ddx = dFdx(vShape), ddy = dFdy(vShape);  // exact: edge distances are affine in position
  float rOut2 = vShape.z * vShape.z, rIn2 = vShape.w * vShape.w;
  float covered = 0.0;
  for (int i = 0; i < SAMPLE_COUNT; ++i) {
    vec2 o = samples[i];
    vec2 q = vShape.xy + o;
    float r2 = dot(q, q);
    vec4 d = vShape + ddx * o.x + ddy * o.y;
    bool inCircle = r2 <= rOut2 && r2 >= rIn2;
    bool inEdges = min(min(d.x, d.y), min(d.z, d.w)) >= 0.0;
    covered += (vKind > 0.5 ? inCircle : inEdges) ? 1.0 : 0.0;
  }
  if (covered == 0.0) discard;
  gl_FragColor = vec4(vColor.rgb, vColor.a * covered / float(SAMPLE_COUNT));
}
)";

GLuint compileShader(GLenum type, const char* source, const char* name) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw RenderError(std::string("compiling the ") + name + " shader failed: " + log);
  }
  return shader;
}

}  // namespace

const std::vector<Vec2>& samplePattern(int samples) {
  // The standard sample positions of Direct3D and Vulkan, given in 1/16 pixel, y down.
  auto inPixels = [](std::vector<Vec2> sixteenths) {
    for (Vec2& o : sixteenths) o /= 16.0;
    return sixteenths;
  };
  static const std::vector<Vec2> p1 = {Vec2(0, 0)};
  static const std::vector<Vec2> p2 = inPixels({Vec2(4, 4), Vec2(-4, -4)});
  static const std::vector<Vec2> p4 = inPixels({Vec2(-2, -6), Vec2(6, -2), Vec2(-6, 2), Vec2(2, 6)});
  static const std::vector<Vec2> p8 = inPixels(
      {Vec2(1, -3), Vec2(-1, 3), Vec2(5, 1), Vec2(-3, -5), Vec2(-5, 5), Vec2(-7, -1), Vec2(3, 7), Vec2(7, -7)});
  static const std::vector<Vec2> p16 = inPixels(
      {Vec2(1, 1), Vec2(-1, -3), Vec2(-3, 2), Vec2(4, -1), Vec2(-5, -2), Vec2(2, 5), Vec2(5, 3), Vec2(3, -5),
       Vec2(-2, 6), Vec2(0, -7), Vec2(-4, -6), Vec2(-6, 4), Vec2(-8, 0), Vec2(7, -4), Vec2(6, 7), Vec2(-7, -8)});
  switch (samples) {
    case 1: return p1;
    case 2: return p2;
    case 4: return p4;
    case 8: return p8;
    case 16: return p16;
    default: throw std::invalid_argument("no sample pattern for " + std::to_string(samples) + " samples");
  }
}

struct Renderer::Impl {
  RenderOptions options;
  Theme colors;
  Image image;  // OSMesa's colour buffer: GL window row y is image row y (see toPixel)
  OsMesaContextPtr context;
  GLuint program = 0;
  GLint positionAttr = -1, colorAttr = -1, shapeAttr = -1, kindAttr = -1;
  ShapeMesh mesh;

  void makeCurrent() {
    if (!OSMesaMakeCurrent(context.get(), image.rgba.data(), GL_UNSIGNED_BYTE, image.width, image.height)) {
      throw RenderError("OSMesaMakeCurrent(" + std::to_string(image.width) + "x" + std::to_string(image.height) +
                        ", GL_UNSIGNED_BYTE) failed");
    }
  }
  void buildMesh(const Drawing& frame, const Camera& camera);
  void buildProgram();
};

void Renderer::Impl::buildProgram() {
  const GLuint vs = compileShader(GL_VERTEX_SHADER, kVertexShader, "vertex");
  const std::vector<Vec2>& pattern = samplePattern(options.msaa);
  std::string header = "#version 130\n#define SAMPLE_COUNT " + std::to_string(pattern.size()) + "\n#define SAMPLES ";
  for (size_t i = 0; i < pattern.size(); ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%svec2(%.6f, %.6f)", i ? ", " : "", pattern[i].x(), pattern[i].y());
    header += buf;
  }
  const std::string fragmentSource = header + "\n" + kFragmentShader;
  const GLuint fs = compileShader(GL_FRAGMENT_SHADER, fragmentSource.c_str(), "fragment");
  program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);  // freed with the program
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    throw RenderError(std::string("linking the shader program failed: ") + log);
  }
  positionAttr = glGetAttribLocation(program, "position");
  colorAttr = glGetAttribLocation(program, "color");
  shapeAttr = glGetAttribLocation(program, "shape");
  kindAttr = glGetAttribLocation(program, "kind");
  glUseProgram(program);
  glUniform2f(glGetUniformLocation(program, "imageSize"), float(options.width), float(options.height));
  checkGl("shader program setup");
}

Renderer::Renderer(const RenderOptions& options) : impl_(std::make_unique<Impl>()) {
  validate(options);
  Impl& m = *impl_;
  m.options = options;
  m.colors = theme(options.themeName);
  m.image = Image(options.width, options.height);

  // No depth, stencil or accumulation buffers: shapes are drawn in painter's order.
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
  m.buildProgram();
}

Renderer::~Renderer() = default;  // the context owns the program; destroying it frees both

const RenderOptions& Renderer::options() const {
  return impl_->options;
}
int Renderer::samples() const {
  return impl_->options.msaa;
}

void Renderer::Impl::buildMesh(const Drawing& f, const Camera& camera) {
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
  // image grown by 8 px so their ends never show.
  for (const Drawing::Circle& circle : f.guideCircles) {
    mesh.ring(toPixel(circle.center), float(circle.radius * scale), float(options.guideWidthPx), c.guide);
  }
  for (const Drawing::Line& line : f.guideLines) {
    const P2 p = toPixel(line.point);
    const double dx = line.direction.x(), dy = -line.direction.y();  // pixel y points down
    if (std::abs(dx) >= std::abs(dy)) {  // mostly horizontal: from the left edge to the right
      const auto yAt = [&](float x) { return float(p[1] + (double(x) - p[0]) * dy / dx); };
      mesh.line({-8.0f, yAt(-8.0f)}, {w + 8.0f, yAt(w + 8.0f)}, float(options.guideWidthPx), c.guide);
    } else {  // mostly vertical: from the top edge to the bottom
      const auto xAt = [&](float y) { return float(p[0] + (double(y) - p[1]) * dx / dy); };
      mesh.line({xAt(-8.0f), -8.0f}, {xAt(h + 8.0f), h + 8.0f}, float(options.guideWidthPx), c.guide);
    }
  }

  for (const Drawing::Spring& s : f.springs) {
    const double t = std::clamp(s.strain / options.strainForFullColor, -1.0, 1.0);
    const Rgb col = t < 0 ? mix(c.springRest, c.springCompressed, -t) : mix(c.springRest, c.springStretched, t);
    mesh.line(toPixel(s.a), toPixel(s.b), float(options.springWidthPx), col);
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

const Image& Renderer::render(const Drawing& frame, const Camera& camera) {
  if (!(camera.height > 0.0)) throw std::invalid_argument("camera height must be positive");
  Impl& m = *impl_;
  m.makeCurrent();
  m.buildMesh(frame, camera);

  const int w = m.options.width, h = m.options.height;
  glViewport(0, 0, w, h);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DITHER);
  // Coverage as alpha over what is drawn; the destination keeps alpha 1.
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);

  const Rgb bg = m.colors.background;
  glClearColor(float(bg.r) / 255.0f, float(bg.g) / 255.0f, float(bg.b) / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);

  if (!m.mesh.vertices().empty()) {
    const ShapeVertex* v = m.mesh.vertices().data();
    const GLsizei stride = sizeof(ShapeVertex);
    glUseProgram(m.program);
    const GLint attrs[] = {m.positionAttr, m.colorAttr, m.shapeAttr, m.kindAttr};
    for (GLint a : attrs) {
      if (a >= 0) glEnableVertexAttribArray(GLuint(a));
    }
    // An attribute the compiler dropped has location −1 and is skipped.
    if (m.positionAttr >= 0) glVertexAttribPointer(GLuint(m.positionAttr), 2, GL_FLOAT, GL_FALSE, stride, &v->x);
    if (m.colorAttr >= 0) glVertexAttribPointer(GLuint(m.colorAttr), 4, GL_UNSIGNED_BYTE, GL_TRUE, stride, v->rgba);
    if (m.shapeAttr >= 0) glVertexAttribPointer(GLuint(m.shapeAttr), 4, GL_FLOAT, GL_FALSE, stride, v->shape);
    if (m.kindAttr >= 0) glVertexAttribPointer(GLuint(m.kindAttr), 1, GL_FLOAT, GL_FALSE, stride, &v->kind);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(m.mesh.vertices().size()));
    for (GLint a : attrs) {
      if (a >= 0) glDisableVertexAttribArray(GLuint(a));
    }
  }
  checkGl("drawing the frame");
  glFinish();
  checkGl("glFinish");
  return m.image;
}

}  // namespace particles::render
