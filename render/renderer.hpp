#pragma once
// Off-screen OpenGL rendering of a FrameSnapshot (DESIGN §9) through OSMesa, Mesa's software
// rasteriser (llvmpipe): no display, no GPU. DISPLAY may be unset.
//
// Anti-aliasing: OSMesa has no multisampled visuals, but its GL 4.5 compatibility context has
// framebuffer objects (measured: Mesa 22.3, llvmpipe, GL_MAX_SAMPLES = 4). We draw into a
// multisampled renderbuffer and resolve it with glBlitFramebuffer into OSMesa's colour buffer.
// msaa = 1 draws straight into that buffer (no anti-aliasing).
//
// Every shape is built on the CPU as triangles in pixel coordinates (lines as quads of a given
// pixel width, discs as fans), drawn opaque in a fixed order: the same snapshot gives the same
// pixels every time (tests check byte equality; a 1280×720 cloth frame was also byte-identical
// with LP_NUM_THREADS = 0, 1, 2 and llvmpipe's default).
//
// Speed (25×25 cloth, 1280×720, 2 shared cores, Mesa 22.3): about 72 frames/s with msaa 4 and
// 220–280 frames/s with msaa 1.

#include <memory>

#include "render/image.hpp"
#include "render/snapshot.hpp"

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
  int msaa = 4;  // samples per pixel: 1 (off), 2 or 4 (llvmpipe's maximum)
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
  const Image& render(const FrameSnapshot& frame, const Camera& camera);

  const RenderOptions& options() const;
  int samples() const;  // the sample count GL actually gave (1 when msaa is off)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace particles::render
