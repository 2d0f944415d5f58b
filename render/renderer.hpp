#pragma once
// Off-screen OpenGL rendering of a Drawing (DESIGN §9) through OSMesa, Mesa's software
// rasteriser (llvmpipe): no display, no GPU. DISPLAY may be unset.
//
// Anti-aliasing is multisampling done in the fragment shader: every primitive carries its true
// boundary (edge distances, or a circle's centre and radii), each pixel is tested at `msaa` sample
// positions (the standard 2/4/8/16 patterns, samplePattern) and the covered share is blended over
// what is already drawn as the fragment's alpha. For one edge over a background this gives the
// same pixel as a multisampled framebuffer's resolve. We do not use llvmpipe's multisampled
// framebuffer: its resolve alone costs ~6 ms of CPU per 1280×720 frame (glBlitFramebuffer or a
// texelFetch shader alike, measured on Mesa 22.3), which ran end-to-end video at 0.6 of the
// encoder's speed; the shader's cost grows only with the pixels shapes touch. msaa = 1 tests the
// pixel centre only: hard edges.
//
// Every shape is built on the CPU as triangles in pixel coordinates (lines as quads of a given
// pixel width, discs as fans), pushed out by a 1 px fringe where they are smoothed, and drawn in a
// fixed order: the same snapshot gives the same pixels every time (tests check byte equality).
//
// Speed: bench/README.md (render-only frames per second for the three demos).

#include <array>
#include <memory>
#include <vector>

#include "render/image.hpp"
#include "core/drawing.hpp"

namespace particles::render {

// The world-to-pixel mapping: `center` appears at the centre of the image and `height` world
// units span the image vertically; pixels are square, world y points up.
struct Camera {
  Vec2 center = Vec2::Zero();
  double height = 3.0;  // world units shown vertically, > 0
};

enum class ThemeName { dark, light };  // dark for the screen, light for printed reports

struct Rgb {
  unsigned char r, g, b;
};

struct Theme {
  Rgb background;
  Rgb particle, fixedParticle;
  Rgb springCompressed, springRest, springStretched;
  Rgb rod;
  Rgb guide;  // circular wires and rails
  Rgb bodyFill, bodyOutline;
  Rgb colliderFill, colliderOutline;
  Rgb mouse, mouseOutline;
};
Theme theme(ThemeName name);

struct Length {
  enum class Unit { pixels, world };
  double value;
  Unit unit;
};

struct RenderOptions {
  int width = 1280;  // pixels
  int height = 720;
  int msaa = 4;  // samples per pixel: one of kSampleCounts (1 is off)
  ThemeName themeName = ThemeName::dark;
  Length particleRadius{4.0, Length::Unit::pixels};
  double springWidthPx = 1.5;
  double rodWidthPx = 3.5;
  double guideWidthPx = 1.5;    // wires and rails
  double outlineWidthPx = 1.5;  // bodies, colliders, cursor
  // |strain| at which a spring reaches the full compressed / stretched colour; in between the
  // colour is interpolated from the at-rest colour.
  double strainForFullColor = 0.2;
};

// The anti-aliasing sample counts there is a pattern for (RenderOptions::msaa).
inline constexpr std::array<int, 5> kSampleCounts = {1, 2, 4, 8, 16};

// The sample positions for each of kSampleCounts: offsets from the pixel centre in
// pixels, x right, y down (Direct3D's and Vulkan's standard patterns; 1 is the centre itself).
// Throws std::invalid_argument for another count.
const std::vector<Vec2>& samplePattern(int samples);

// Throws std::invalid_argument when a size, width or sample count is out of range.
void validate(const RenderOptions& options);

class Renderer {
 public:
  // Makes the OSMesa context and framebuffers. Throws RenderError naming the failing call (for
  // instance OSMesaCreateContextAttribs, or an incomplete framebuffer) and std::invalid_argument
  // for bad options.
  explicit Renderer(const RenderOptions& options);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws the snapshot. The image is owned by the renderer and valid until the next call.
  // Throws RenderError if GL reports an error.
  const Image& render(const Drawing& frame, const Camera& camera);

  const RenderOptions& options() const;
  int samples() const;  // samples per pixel (options().msaa)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace particles::render
