// The renderer (render/renderer.hpp) and System::draw (core/drawing.hpp): what lands where in a
// frame, strain colours, anti-aliasing, determinism, and the errors it reports.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <numbers>
#include <optional>
#include <set>
#include <string>

#include "core/constraints/circular_wire_constraint.hpp"
#include "core/forces/damped_spring_force.hpp"
#include "core/colliders/disk_collider.hpp"
#include "core/colliders/half_plane_collider.hpp"
#include "core/constraints/horizontal_line_constraint.hpp"
#include "core/forces/mouse_spring_force.hpp"
#include "render/errors.hpp"
#include "render/renderer.hpp"
#include "render/shader_program.hpp"
#include "core/drawing.hpp"
#include "core/system.hpp"
#include "render_support.hpp"
#include "core/constraints/rod_constraint.hpp"

using namespace particles;
using namespace particles::render;
using particles::test::projectToPixel;
using particles::test::sameRgb;

namespace {

// Unsets DISPLAY for its lifetime: the renderer must not need an X server.
class NoDisplay {
 public:
  NoDisplay() {
    if (const char* d = std::getenv("DISPLAY")) saved_ = d;
    ::unsetenv("DISPLAY");
  }
  ~NoDisplay() {
    if (saved_) ::setenv("DISPLAY", saved_->c_str(), 1);
  }

 private:
  std::optional<std::string> saved_;
};

RenderOptions smallOptions(int msaa = 4) {
  return particles::test::smallRenderOptions(320, 240, msaa);
}

std::string rgbText(const std::uint8_t* p) {
  return std::to_string(p[0]) + "," + std::to_string(p[1]) + "," + std::to_string(p[2]);
}

}  // namespace

TEST_CASE("System::draw describes positions, spring strains, constraints, colliders and the active mouse") {
  SystemBuilder b;
  const int a = b.addParticle({Vec2(0, 0), Vec2::Zero(), 1.0, true, "a"});
  const int c = b.addParticle({Vec2(1.5, 0), Vec2::Zero(), 1.0, false, "c"});
  const int d = b.addParticle({Vec2(0, 1), Vec2::Zero(), 1.0, false, "d"});
  const int body = b.addRigidBody({Vec2(2, 2), Vec2::Zero(), 0.3, 0.0, Vec2(0.4, 0.2), 1.0, "box"});
  auto& springs = b.emplaceForce<DampedSpringForce>();
  springs.add({Endpoint::ofParticle(a), Endpoint::ofParticle(c), 1.0, 10, 0});  // |l| 1.5, rest 1: +0.5
  springs.add({Endpoint::ofParticle(c), Endpoint::ofBody(body, Vec2(0.2, 0)), 4.0, 10, 0});
  b.emplaceForce<MouseSpringForce>(MouseScript{Endpoint::ofParticle(d), 0.0, 1.0, {Vec2(3, 3)}, 5});
  b.emplaceForce<MouseSpringForce>(MouseScript{Endpoint::ofParticle(c), 2.0, 3.0, {Vec2(-3, 3)}, 5});  // later
  b.addConstraint(std::make_unique<RodConstraint>(a, d, 1.0));
  for (int p : {c, d}) b.addConstraint(std::make_unique<CircularWireConstraint>(p, Vec2(0, 0), 1.5));
  for (int p : {c, d}) b.addConstraint(std::make_unique<HorizontalLineConstraint>(p, 0.5));
  b.addCollider(std::make_unique<HalfPlaneCollider>(Vec2(0, 2), -1.5));
  b.addCollider(std::make_unique<DiskCollider>(Vec2(1, -1), 0.25));
  const System system = b.build();

  const Drawing f = system.draw();
  CHECK(f.time == 0.0);
  REQUIRE(f.particles.size() == 3);
  CHECK(f.particles[1] == Vec2(1.5, 0));
  CHECK(f.particleFixed == std::vector<char>{1, 0, 0});
  REQUIRE(f.bodies.size() == 1);
  CHECK(f.bodies[0].center == Vec2(2, 2));
  CHECK(f.bodies[0].angle == 0.3);
  CHECK(f.bodies[0].size == Vec2(0.4, 0.2));
  REQUIRE(f.springs.size() == 2);
  CHECK(f.springs[0].strain == doctest::Approx(0.5));
  // The second spring ends on the body's anchor, rotated by 0.3 rad about its centre.
  CHECK(f.springs[1].b.x() == doctest::Approx(2 + 0.2 * std::cos(0.3)));
  CHECK(f.springs[1].b.y() == doctest::Approx(2 + 0.2 * std::sin(0.3)));
  REQUIRE(f.rods.size() == 1);
  CHECK(f.rods[0].b == Vec2(0, 1));
  CHECK(f.guideCircles.size() == 1);  // two beads on one wire: one circle
  CHECK(f.guideLines.size() == 1);
  REQUIRE(f.halfPlanes.size() == 1);
  CHECK(f.halfPlanes[0].normal == Vec2(0, 1));
  CHECK(f.disks.size() == 1);
  REQUIRE(f.cursors.size() == 1);  // the second script starts at t = 2
  CHECK(f.cursors[0].target == Vec2(3, 3));
  CHECK(f.cursors[0].grabbed == Vec2(0, 1));
}

TEST_CASE("particles land where the camera projects them, and nothing else is drawn") {
  NoDisplay noDisplay;
  const System system = particles::test::fallingParticles();
  const Drawing frame = system.draw();
  const RenderOptions options = smallOptions();
  const Palette colors = theme(options.themeName);
  // Off-centre camera: a frame drawn shifted, flipped or at the wrong scale puts the discs elsewhere.
  const Camera camera{Vec2(0.25, -0.1), 2.4};
  Renderer renderer(options);
  CHECK(renderer.samples() == 4);
  const Image& image = renderer.render(frame, camera);
  REQUIRE(image.width == 320);
  REQUIRE(image.height == 240);

  std::vector<Vec2> centres;
  for (const Vec2& p : frame.particles) centres.push_back(projectToPixel(p, camera, image.width, image.height));
  for (const Vec2& c : centres) {
    INFO("particle at pixel (" << c.x() << ", " << c.y() << ")");
    REQUIRE(c.x() > 8);
    REQUIRE(c.x() < image.width - 8);
    REQUIRE(c.y() > 8);
    REQUIRE(c.y() < image.height - 8);
    // Inside the 6 px disc every sample is covered: exactly the particle colour.
    for (const Vec2& off : {Vec2(0, 0), Vec2(3, 0), Vec2(-3, 0), Vec2(0, 3), Vec2(0, -3)}) {
      const std::uint8_t* px = image.pixel(int(c.x() + off.x()), int(c.y() + off.y()));
      CHECK_MESSAGE(sameRgb(px, colors.particle), "got " << rgbText(px));
    }
    // Pixels whose centres are 6.5–7.5 px out are background: shifted 2 px, the disc covers one.
    for (const Vec2& off : {Vec2(7, 0), Vec2(-7, 0), Vec2(0, 7), Vec2(0, -7)}) {
      const std::uint8_t* px = image.pixel(int(c.x() + off.x()), int(c.y() + off.y()));
      CHECK_MESSAGE(sameRgb(px, colors.background), "got " << rgbText(px) << " at offset " << off.transpose());
    }
  }
  // Every 7th pixel at least 9 px from all discs is pure background.
  int sampled = 0;
  for (int y = 0; y < image.height; y += 7) {
    for (int x = 0; x < image.width; x += 7) {
      bool nearParticle = false;
      for (const Vec2& c : centres) nearParticle = nearParticle || (Vec2(x + 0.5, y + 0.5) - c).norm() < 9.0;
      if (nearParticle) continue;
      ++sampled;
      const std::uint8_t* px = image.pixel(x, y);
      if (!sameRgb(px, colors.background)) FAIL_CHECK("pixel (" << x << ", " << y << ") is " << rgbText(px));
    }
  }
  CHECK(sampled > 1500);
}

TEST_CASE("world-unit particle radius scales with the camera") {
  const System system = particles::test::fallingParticles();
  RenderOptions options = smallOptions();
  options.particleRadius = {0.05, Length::Unit::world};  // 0.05 · 240 px / 2.4 = 5 px
  const Palette colors = theme(options.themeName);
  const Camera camera{Vec2(0.1, -0.1), 2.4};
  Renderer renderer(options);
  const Image& image = renderer.render(system.draw(), camera);
  const Vec2 c = projectToPixel(Vec2(0.2, 0.6), camera, 320, 240);
  CHECK(sameRgb(image.pixel(int(c.x() + 3), int(c.y())), colors.particle));    // 3.5 px from the centre
  CHECK(sameRgb(image.pixel(int(c.x() + 7), int(c.y())), colors.background));  // 7.5 px
}

TEST_CASE("springs are coloured by strain: compressed, at rest, stretched") {
  // Three horizontal springs of rest length 1, drawn 4 px wide, at world y = 0.6, 0, −0.6.
  Drawing f;
  f.springs = {{Vec2(-0.5, 0.6), Vec2(0.5, 0.6), -0.5},
               {Vec2(-0.5, 0), Vec2(0.5, 0), 0.0},
               {Vec2(-0.5, -0.6), Vec2(0.5, -0.6), 0.5}};
  RenderOptions options = smallOptions();
  options.springWidthPx = 4.0;
  const Palette colors = theme(options.themeName);
  const Camera camera{Vec2(0, 0), 2.0};
  Renderer renderer(options);
  const Image& image = renderer.render(f, camera);
  auto at = [&](double y) {
    const Vec2 p = projectToPixel(Vec2(0.1, y), camera, 320, 240);
    return image.pixel(int(p.x()), int(p.y()));
  };
  CHECK_MESSAGE(sameRgb(at(0.6), colors.springCompressed), rgbText(at(0.6)));
  CHECK_MESSAGE(sameRgb(at(0.0), colors.springRest), rgbText(at(0.0)));
  CHECK_MESSAGE(sameRgb(at(-0.6), colors.springStretched), rgbText(at(-0.6)));
  CHECK(sameRgb(at(0.3), colors.background));
}

TEST_CASE("every kind of shape is drawn in its theme colour") {
  Drawing f;
  f.halfPlanes = {{Vec2(0, 1), -0.8}};  // solid below y = −0.8
  f.disks = {{Vec2(-0.8, 0.5), 0.2}};
  f.bodies = {{Vec2(0.8, 0.5), 0.0, Vec2(0.4, 0.2)}};
  f.rods = {{Vec2(-0.5, -0.3), Vec2(0.5, -0.3)}};
  f.guideLines = {{Vec2(0, 0.8), Vec2(1, 0)}};
  f.guideCircles = {{Vec2(0, 0.3), 0.3}};
  f.cursors = {{Vec2(0.0, -0.55), Vec2(-0.9, -0.55)}};
  for (ThemeName name : {ThemeName::dark, ThemeName::light}) {
    RenderOptions options = smallOptions();
    options.themeName = name;
    options.guideWidthPx = 4.0;  // wide enough to cover whole pixel rows
    options.springWidthPx = 4.0;
    const Palette colors = theme(name);
    const Camera camera{Vec2(0, 0), 2.0};
    Renderer renderer(options);
    const Image& image = renderer.render(f, camera);
    auto at = [&](double x, double y) {
      const Vec2 p = projectToPixel(Vec2(x, y), camera, 320, 240);
      return image.pixel(int(p.x()), int(p.y()));
    };
    CHECK(sameRgb(at(0.0, 0.9), colors.background));
    CHECK(sameRgb(at(0.0, -0.95), colors.colliderFill));
    CHECK(sameRgb(at(-0.8, 0.5), colors.colliderFill));
    CHECK(sameRgb(at(0.8, 0.5), colors.bodyFill));
    CHECK(sameRgb(at(0.0, -0.3), colors.rod));
    CHECK(sameRgb(at(-1.2, 0.8), colors.guide));                  // the rail spans the whole width
    CHECK(sameRgb(at(0.0, 0.0), colors.guide));                   // bottom of the wire circle
    const std::uint8_t* inArrow = image.pixel(160 + 2, 186 + 6);  // tip at (0, −0.55) → pixel (160, 186)
    CHECK_MESSAGE(sameRgb(inArrow, colors.mouse), rgbText(inArrow));
    CHECK(sameRgb(at(-0.6, -0.55), colors.mouse));  // the line to the grabbed point
  }
  CHECK(theme(ThemeName::dark).background.r < 64);
  CHECK(theme(ThemeName::light).background.r > 192);
}

TEST_CASE("multisampling smooths edges, and msaa 1 gives hard edges") {
  const System system = particles::test::fallingParticles();
  const Camera camera{Vec2(0, 0), 2.4};
  auto distinctColours = [&](int msaa) {
    Renderer renderer(smallOptions(msaa));
    const Image& image = renderer.render(system.draw(), camera);
    std::set<std::uint32_t> colours;
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
      colours.insert(std::uint32_t(image.rgba[i]) << 16 | std::uint32_t(image.rgba[i + 1]) << 8 | image.rgba[i + 2]);
    }
    return colours.size();
  };
  CHECK(distinctColours(1) == 2);  // background and particle, nothing in between
  CHECK(distinctColours(4) > 2);   // partially covered pixels at the disc edges
}

TEST_CASE("the same drawing renders to the same bytes") {
  const System system = particles::test::fallingParticles();
  const Drawing frame = system.draw();
  const Camera camera{Vec2(0.1, 0), 2.4};
  Renderer renderer(smallOptions());
  const Image first = renderer.render(frame, camera);
  Drawing other = frame;
  other.particles[0] += Vec2(0.3, 0);
  const Image moved = renderer.render(other, camera);
  CHECK(moved != first);
  CHECK(renderer.render(frame, camera) == first);
  Renderer second(smallOptions());  // a fresh context too
  CHECK(second.render(frame, camera) == first);
}

TEST_CASE("renderer options are checked") {
  RenderOptions o = smallOptions();
  o.msaa = 0;
  CHECK_THROWS_AS(Renderer{o}, std::invalid_argument);
  for (int msaa : {3, 5, 32, 64}) CHECK_THROWS_AS(Renderer{smallOptions(msaa)}, std::invalid_argument);
  o = smallOptions();
  o.width = 0;
  CHECK_THROWS_AS(Renderer{o}, std::invalid_argument);
  Renderer renderer(smallOptions());
  CHECK_THROWS_AS(renderer.render(Drawing{}, Camera{Vec2::Zero(), 0.0}), std::invalid_argument);
}

namespace {

// A 64 × 48 image whose camera maps world (x, y) to pixel (x, −y): one world unit per pixel.
constexpr int kCoverageW = 64, kCoverageH = 48;
const Camera kPixelCamera{Vec2(32, -24), 48.0};

RenderOptions pixelCameraOptions(int samples = 4) {
  RenderOptions o;
  o.width = kCoverageW;
  o.height = kCoverageH;
  o.msaa = samples;
  return o;
}

// Every pixel must be the background blended towards `fg` by the share of the pixel's samples
// that `inside` accepts (sample points in pixels, x right, y down): what a multisampled
// framebuffer resolves to. Returns the summed coverage (pixels).
double checkCoverage(const Image& image, render::Rgb bg, render::Rgb fg, int samples, const std::function<bool(Vec2)>& inside) {
  const std::vector<Vec2>& pattern = samplePattern(samples);
  REQUIRE(int(pattern.size()) == samples);
  double total = 0;
  int wrong = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      int k = 0;
      for (const Vec2& o : pattern) k += inside(Vec2(x + 0.5, y + 0.5) + o) ? 1 : 0;
      const double a = double(k) / samples;
      total += a;
      const std::uint8_t* px = image.pixel(x, y);
      const double expected[3] = {bg.r + (fg.r - bg.r) * a, bg.g + (fg.g - bg.g) * a, bg.b + (fg.b - bg.b) * a};
      for (int ch = 0; ch < 3; ++ch) {
        // ±2: blending rounds the coverage to 8 bits and the result again.
        if (std::abs(double(px[ch]) - expected[ch]) > 2.0 && ++wrong <= 5) {
          FAIL_CHECK("pixel (" << x << ", " << y << ") channel " << ch << " is " << int(px[ch]) << ", expected "
                               << expected[ch] << " (" << k << " of " << samples << " samples covered)");
        }
      }
    }
  }
  CHECK(wrong == 0);
  return total;
}

}  // namespace

TEST_CASE("sample patterns lie inside the pixel, one sample per row and per column") {
  // Distinct x and y offsets ("N rooks"): a vertical or horizontal edge crossing the pixel passes
  // through all N + 1 coverage levels, the point of the standard patterns.
  for (int samples : kSampleCounts) {
    CAPTURE(samples);
    const std::vector<Vec2>& pattern = samplePattern(samples);
    REQUIRE(int(pattern.size()) == samples);
    std::set<double> xs, ys;
    Vec2 mean = Vec2::Zero();
    for (const Vec2& o : pattern) {
      CHECK(std::abs(o.x()) <= 0.5);
      CHECK(std::abs(o.y()) <= 0.5);
      xs.insert(o.x());
      ys.insert(o.y());
      mean += o / samples;
    }
    CHECK(int(xs.size()) == samples);
    CHECK(int(ys.size()) == samples);
    CHECK(mean.norm() < 0.07);  // centred on the pixel
  }
  CHECK_THROWS_AS(samplePattern(3), std::invalid_argument);
}

TEST_CASE("each pixel of a disc is blended by the share of its samples inside the circle") {
  const Vec2 centre(20.3, 17.8);  // pixels; off the pixel grid on purpose
  const double radius = 6.2;
  Drawing frame;
  frame.particles = {Vec2(centre.x(), -centre.y())};
  frame.particleFixed = {0};
  for (int samples : kSampleCounts) {
    CAPTURE(samples);
    RenderOptions o = pixelCameraOptions(samples);
    o.particleRadius = {radius, Length::Unit::pixels};
    Renderer renderer(o);
    CHECK(renderer.samples() == samples);
    const Palette colors = theme(o.themeName);
    const double area = checkCoverage(renderer.render(frame, kPixelCamera), colors.background, colors.particle, samples,
                                      [&](Vec2 p) { return (p - centre).norm() <= radius; });
    // More samples, closer to the true area π r² (120.8 px²).
    const double error = std::abs(area / (std::numbers::pi * radius * radius) - 1.0);
    if (samples >= 4) CHECK(error < 0.03);
    if (samples == 16) CHECK(error < 0.01);
  }
}

TEST_CASE("each pixel of a slanted line is blended by the share of its samples inside the line") {
  const Vec2 a(8.2, 30.7), b(55.6, 11.1);  // pixels
  const double width = 3.3;
  Drawing frame;
  frame.springs = {{Vec2(a.x(), -a.y()), Vec2(b.x(), -b.y()), 0.0}};  // at rest: the rest colour
  const Vec2 along = (b - a).normalized(), across(-along.y(), along.x());
  for (int samples : {1, 4, 16}) {
    CAPTURE(samples);
    RenderOptions o = pixelCameraOptions(samples);
    o.springWidthPx = width;
    Renderer renderer(o);
    const Palette colors = theme(o.themeName);
    checkCoverage(renderer.render(frame, kPixelCamera), colors.background, colors.springRest, samples, [&](Vec2 p) {
      const double t = (p - a).dot(along), n = (p - a).dot(across);
      return t >= 0 && t <= (b - a).norm() && std::abs(n) <= 0.5 * width;
    });
  }
}

TEST_CASE("a shape drawn in convex pieces shows no seams between them") {
  // The mouse cursor's arrow is four pieces; inside it, away from its outline, every pixel must be
  // exactly the cursor colour (a smoothed shared edge would leave a darker seam).
  Drawing frame;
  const Vec2 tip(21.37, 9.61);  // pixels
  frame.cursors = {{Vec2(tip.x(), -tip.y()), Vec2(tip.x(), -tip.y())}};
  const RenderOptions o = pixelCameraOptions();
  Renderer renderer(o);
  const Image& image = renderer.render(frame, kPixelCamera);
  const Palette colors = theme(o.themeName);
  // The arrow's outline, relative to its tip (render/frame_mesh.cpp), and distances to it.
  const std::vector<Vec2> arrow = {Vec2(0, 0),   Vec2(0, 17),   Vec2(4.5, 13), Vec2(7.5, 20),
                                   Vec2(10, 19), Vec2(7, 12.2), Vec2(12, 12.2)};
  auto distanceToOutline = [&](Vec2 p) {
    double d = 1e9;
    for (size_t i = 0; i < arrow.size(); ++i) {
      const Vec2 a = arrow[i], ab = arrow[(i + 1) % arrow.size()] - a;
      const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      d = std::min(d, (p - a - t * ab).norm());
    }
    return d;
  };
  auto inside = [&](Vec2 p) {  // even-odd rule
    bool in = false;
    for (size_t i = 0, j = arrow.size() - 1; i < arrow.size(); j = i++) {
      const Vec2 a = arrow[i], b = arrow[j];
      if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y())) {
        in = !in;
      }
    }
    return in;
  };
  int checked = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const Vec2 p = Vec2(x + 0.5, y + 0.5) - tip;
      if (!inside(p) || distanceToOutline(p) < 1.5) continue;  // outline 1.25 px + the samples' reach
      ++checked;
      const std::uint8_t* px = image.pixel(x, y);
      CHECK_MESSAGE(sameRgb(px, colors.mouse), "pixel (" << x << ", " << y << ") is " << rgbText(px));
    }
  }
  CHECK(checked > 25);  // the interior crosses every shared edge
}
