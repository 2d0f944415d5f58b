#pragma once
// Internal to render/: the resident path (Raster::resident). A scene's springs and
// particles stay in GL's buffers: the springs' topology (each spring's two particle indices and
// rest length) is uploaded once, when a drawing brings a topology the program does not hold yet
// (Drawing::springTopology, the same object from frame to frame), and each frame sends only the
// particles' positions, 8 bytes a particle, plus their fixed flags when those change. Particles
// are drawn as instances of one square, springs as instances of one quad expanded in the vertex
// shader from its ends' positions; both feed the triangle path's coverage shader
// (render/shader_program.hpp) the boundary ShapeSink would have given them (render/shape_mesh.hpp:
// the line's quad grown by its fringe, the disc's centre offsets and radii), compiled for the
// boundaries each program draws (springs: edges; particles: discs, with edges too only in a frame
// that has a fixed particle, drawn as a square), and each spring gets
// its strain colour (render/theme.hpp's springColor) from its length there. A frame's look
// (render/frame_look.hpp) may give each particle its colour and radius and each spring its
// colour: those go to GL as buffers beside the positions, each frame it has them (uploadLook). GL draws an instanced
// draw's primitives in instance order, so painter's order and the blending are the triangle
// path's: the same pixels up to the float rounding of the geometry, now done by the GPU
// (tests/test_render_resident.cpp measures how close). Positions go to GL as pixels computed on
// the CPU as every path computes them (render/frame_mesh.hpp's particlePixels).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/drawing.hpp"
#include "render/theme.hpp"

namespace particles::render {

struct GlFunctions;  // render/gl_functions.hpp

// What the resident path draws with, per frame: the look (render/render_options.hpp, the theme)
// resolved to pixels and colours.
struct ResidentLook {
  float particleRadiusPx = 4.0f;
  float springWidthPx = 1.5f;
  double pixelsPerUnit = 1.0;       // for the springs' strain, from their pixel lengths
  double strainForFullColor = 0.2;  // RenderOptions::strainForFullColor
  Palette colors{};
};

class ResidentProgram {
 public:
  // Compiles the springs' and the particles' programs for `samples` per pixel in the current GL
  // context, whose functions `gl` are, and makes their buffers there; `flipY` and the size as
  // ShaderProgram's. Throws RenderError with the compiler's log.
  ResidentProgram(const GlFunctions& gl, int samples, int width, int height, bool flipY);
  // No destructor: the programs and buffers are freed with their context (as ShaderProgram's).
  ResidentProgram(const ResidentProgram&) = delete;
  ResidentProgram& operator=(const ResidentProgram&) = delete;

  // Whether a frame of this many particles and springs by index fits GL's texture buffers
  // (GL_MAX_TEXTURE_BUFFER_SIZE texels each); one that does not must take another path.
  bool fits(size_t particles, size_t springs) const;

  // Sends the frame's particles: their positions in pixels (x, y per particle) and their fixed
  // flags (1 fixed; a shorter list leaves the rest free), which go to GL only when they differ
  // from the last frame's; and the springs' topology (null: none) when it is not the one GL holds.
  void upload(std::span<const float> pixels, std::span<const char> fixed,
              const std::shared_ptr<const Drawing::SpringTopology>& springs);
  // Sends the frame's look for what this program draws: a colour (straight alpha) and a radius in
  // pixels per particle, a colour per spring by index; an empty list draws with ResidentLook's
  // theme colours, radius and strain colours instead. Call after upload, every frame: a list given
  // once is not kept for the next. Throws std::invalid_argument for a list of another length than
  // the particles or springs uploaded.
  void uploadLook(std::span<const Rgba> particleColors, std::span<const float> particleRadiiPx,
                  std::span<const Rgba> springColors);
  // Draws the uploaded springs, or particles, over what the frame holds, in the current context.
  void drawSprings(const ResidentLook& look) const;
  void drawParticles(const ResidentLook& look) const;

  // How many times the topology went to GL (tests: once for a whole render).
  long topologyUploads() const { return topologyUploads_; }

 private:
  enum Buffer { kPositions, kFixed, kEnds, kRest, kParticleColors, kParticleRadii, kSpringColors, kBufferCount };
  struct Program {
    unsigned name = 0;
    int corner = -1;  // its `corner` attribute's location
  };
  // Fills buffer `b` with `bytes` (growing its store when needed, as the tile path does).
  void fill(Buffer b, const void* data, size_t bytes);
  void drawInstances(const Program& program, size_t instances) const;

  const GlFunctions& gl_;
  Program springs_, particles_;
  Program freeParticles_;  // the particles' for a frame with none fixed: discs only
  unsigned buffers_[kBufferCount] = {};
  unsigned textures_[kBufferCount] = {};
  size_t capacity_[kBufferCount] = {};
  long long maxTexels_ = 0;
  size_t particleCount_ = 0, springCount_ = 0;
  std::shared_ptr<const Drawing::SpringTopology> topology_;  // the one GL holds, kept alive
  size_t particlesNeeded_ = 0;  // the topology's largest particle index + 1
  std::vector<std::uint8_t> fixed_;                           // the flags GL holds
  bool anyFixed_ = false;                                     // whether one of them is 1
  std::vector<std::uint8_t> flags_;                           // scratch: this frame's
  long topologyUploads_ = 0;
  // Whether this frame's look gave the particles' colours, their radii, the springs' colours.
  bool ownParticleColors_ = false, ownParticleRadii_ = false, ownSpringColors_ = false;
};

}  // namespace particles::render
