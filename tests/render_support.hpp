#pragma once
// Helpers shared by the render tests: a scratch directory and small scenes.

#include <doctest/doctest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <set>
#include <utility>
#include <string>
#include <vector>

#include "core/forces/gravity_force.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"
#include "render/image.hpp"
#include "render/image_compare.hpp"
#include "render/renderer.hpp"
#include "render/render_options.hpp"
#include "sanitizer.hpp"
#include "scenario/scenario.hpp"
#include "source_tree.hpp"
#include "support/video_probe.hpp"

namespace particles::test {

// The sample counts a comparison of pixels draws at: all of render::kSampleCounts, but under a
// sanitizer the fewest and the most (1 and 16 today). There every buffer llvmpipe allocates for a
// frame comes from the sanitizer's allocator, which made the comparisons that draw the demos at
// every count the costliest cases of the sanitizer stage; the counts between run the same code
// with other numbers, the default among them is what the other tests draw at, and the plain build
// compares them all.
inline std::vector<int> sampleCountsToCompare() {
  if (!kUnderSanitizer) return {render::kSampleCounts.begin(), render::kSampleCounts.end()};
  return {render::kSampleCounts.front(), render::kSampleCounts.back()};
}

// A fresh directory under the system's temp dir, removed with everything in it at scope exit.
class ScratchDir {
 public:
  ScratchDir() {
    static std::atomic<int> n{0};
    path_ = std::filesystem::temp_directory_path() /
            ("particles_render_test_" + std::to_string(::getpid()) + "_" + std::to_string(n++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  // Names of the entries directly in the directory.
  std::set<std::string> entries() const { return listing(path_); }
  static std::set<std::string> listing(const std::filesystem::path& dir) {
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
  }

 private:
  std::filesystem::path path_;
};

// Three free particles at asymmetric positions under gravity: falls, so frames differ in time.
inline System fallingParticles() {
  SystemBuilder b;
  for (const Vec2& p : {Vec2(0.2, 0.6), Vec2(-0.7, -0.3), Vec2(0.9, -0.8)}) {
    ParticleSpec spec;
    spec.pos = p;
    b.addParticle(spec);
  }
  b.emplaceForce<GravityForce>(Vec2(0, -1.0));
  return b.build();
}

// A small frame with 6 px particles: shapes far enough apart to check one by one, quick to draw.
inline render::RenderOptions smallRenderOptions(int width = 320, int height = 240, int msaa = 4) {
  render::RenderOptions o;
  o.width = width;
  o.height = height;
  o.msaa = msaa;
  o.particleRadius = {6.0, render::Length::Unit::pixels};
  return o;
}

// A frame of width × height at `msaa` samples per pixel, drawn by `raster`'s path; the rest default.
inline render::RenderOptions rasterOptions(int width, int height, int msaa, render::Raster raster) {
  render::RenderOptions o;
  o.width = width;
  o.height = height;
  o.msaa = msaa;
  o.raster = raster;
  return o;
}

// Where camera and image size put a world point, in pixels from the top-left (x right, y down).
inline Vec2 projectToPixel(const Vec2& p, const render::Camera& camera, int width, int height) {
  const double scale = double(height) / camera.height;
  return {0.5 * width + (p.x() - camera.center.x()) * scale, 0.5 * height - (p.y() - camera.center.y()) * scale};
}

inline bool sameRgb(const std::uint8_t* px, render::Rgb c) {
  return px[0] == c.r && px[1] == c.g && px[2] == c.b;
}

// What every decoded video is checked for: its codec, size and frame count.
inline void checkVideo(const VideoInfo& info, const std::string& codec, int width, int height, long frames) {
  CHECK(info.codec == codec);
  CHECK(info.width == width);
  CHECK(info.height == height);
  CHECK(info.frames == frames);
}

// A demo scenario (scenarios/NAME.yaml, with `overrides`) advanced to `at` seconds: its drawing
// (springs by position), the same state drawn with its springs by index where it can be
// (SpringDetail::topology, as `particles render` draws), and its camera.
struct DemoFrame {
  Drawing drawing;
  render::Camera camera;
  Drawing byIndex;
};

inline DemoFrame demoFrame(const std::string& name, double at, const std::vector<scenario::Override>& overrides = {}) {
  scenario::Scenario s = scenario::loadScenarioFile(kScenarios / (name + ".yaml"), overrides);
  Stepper(s.system, s.simulation.integrator, s.simulation.dt).advanceTo(at);
  DemoFrame frame{s.system.draw(), {s.render.viewCenter, s.render.viewHeight}, {}};
  s.system.draw(frame.byIndex, SpringDetail::topology);
  return frame;
}

// The three demos at a moment each (springs strained, bodies, contacts, the cursor) at 1280×720,
// at every sample count (sampleCountsToCompare), drawn by the triangle path from the springs by
// position and by `path`: from the springs by index with `byIndex`, else by position. Checks that
// the two are within the golden tolerance (a difference over 16 in at most `tieShare` of the
// pixels, the manifest's 0.02 % unless a path decides ties otherwise; at 1 sample 0.15 %, where an
// edge along pixel centres ties a whole row), and that at most `roundingShare` of the pixels
// (0.15 % at 1 sample) differ by more than `rounding`.
inline void checkDemoFramesOnPath(render::Raster path, bool byIndex, int rounding, double roundingShare,
                                  double tieShare = 0.0002) {
  for (const auto& [name, at] : {std::pair<std::string, double>{"cloth", 2.5}, {"soft_body", 20.0}, {"rigid_chain", 3.0}}) {
    const DemoFrame f = demoFrame(name, at);
    for (int msaa : sampleCountsToCompare()) {
      CAPTURE(name);
      CAPTURE(msaa);
      render::RenderOptions o;
      o.msaa = msaa;  // the default 1280×720
      o.raster = render::Raster::triangles;
      render::Renderer triangles(o);
      o.raster = path;
      render::Renderer other(o);
      const render::Image expected = triangles.render(f.drawing, f.camera);
      const render::Image& actual = other.render(byIndex ? f.byIndex : f.drawing, f.camera);
      const double share = msaa == 1 ? 0.0015 : tieShare;
      const render::ImageComparison golden = render::compareImages(expected, actual, {16, share});
      CHECK_MESSAGE(golden.passed, golden.differing, " pixels differ by more than 16");
      const render::ImageComparison close =
          render::compareImages(expected, actual, {rounding, msaa == 1 ? 0.0015 : roundingShare});
      CHECK_MESSAGE(close.passed, close.differing, " pixels differ by more than ", rounding);
    }
  }
}

}  // namespace particles::test
