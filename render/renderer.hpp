#pragma once
// Off-screen OpenGL rendering of a Drawing (docs/physics.md §9) through EGL or OSMesa
// (render/gl_backend.hpp) on Mesa's software rasteriser, llvmpipe: no display, no GPU (unless
// asked for). DISPLAY may be unset.
//
// Anti-aliasing is multisampling done in the fragment shader: every primitive carries its true
// boundary (edge distances, or a circle's centre and radii), each pixel is tested at `msaa` sample
// positions (the standard 2/4/8/16 patterns, samplePattern) and the covered share is blended over
// what is already drawn as the fragment's alpha. For one edge over a background this gives the
// same pixel as a multisampled framebuffer's resolve. We do not use llvmpipe's multisampled
// framebuffer: its resolve alone (glBlitFramebuffer or a texelFetch shader alike, on Mesa 22.3)
// slowed end-to-end video well below the encoder's speed (bench/README.md, "Coverage in the shader");
// the shader's cost grows only with the pixels shapes touch. msaa = 1 tests the
// pixel centre only: hard edges.
//
// Without a GPU the frames are drawn without GL by default: the cpu path (Raster::cpu,
// render/tile_composite.hpp) composites the tile path's records on the program's own threads,
// straight into the image, with the shader's coverage and blending. On the resident path
// (Raster::resident, render/resident_program.hpp) a scene's springs and particles stay in GL's
// buffers and each frame sends their positions only; everything else is built as below.
//
// Every shape is built on the CPU as triangles in pixel coordinates (lines as quads of a given
// pixel width, discs as fans), pushed out by a 1 px fringe where they are smoothed, and drawn in a
// fixed order: the same drawing gives the same pixels every time (tests check byte equality).
// The parts: render/theme.hpp (colours), render/frame_mesh.hpp (the triangles, no GL),
// render/shader_program.hpp (the coverage shader), render/gl_context.hpp (the GL context, one file
// pair per backend: render/egl_context.hpp, render/osmesa_context.hpp).
//
// Speed: bench/README.md (render-only frames per second for the three demos).

#include <memory>

#include "core/drawing.hpp"
#include "core/worker_pool.hpp"
#include "render/frame_look.hpp"
#include "render/gl_backend.hpp"
#include "render/image.hpp"
#include "render/render_options.hpp"
#include "render/theme.hpp"

namespace particles::render {

class Renderer {
 public:
  // Makes the GL context of `gl` (auto: EGL, else OSMesa) and its framebuffer. Throws RenderError
  // naming the failing call (for instance eglInitialize, OSMesaCreateContextAttribs, or an
  // incomplete framebuffer) and std::invalid_argument for bad options or a backend this build
  // lacks.
  explicit Renderer(const RenderOptions& options, const GlRequest& gl = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws the frame. The image is owned by the renderer and valid until the next call.
  // Throws RenderError if GL reports an error, std::invalid_argument for a spring topology that
  // names particles the frame lacks. With a pool, a large frame's shapes are built and binned on
  // its threads (the tile path, render/tile_bins.hpp): the same pixels for every count. The frame's
  // springs may come by position or by index (System::draw's SpringDetail, the better for a
  // render: the resident path keeps them in GL's buffers, and the others need no list of them).
  // With a look (render/frame_look.hpp; null or empty: the theme's), its colours, radii, trails
  // and arrows, on every path: the resident path sends its particle and spring colours and radii
  // beside the positions and draws its trails and arrows with the CPU's shapes. Translucent
  // shapes agree between paths within a unit per channel (tests/test_render_frame_look.cpp);
  // a look list of the wrong length throws std::invalid_argument naming it. The look is read
  // during the call only (as the frame is), by submit too.
  const Image& render(const Drawing& frame, const Camera& camera, WorkerPool* pool = nullptr,
                      const FrameLook* look = nullptr);
  // render in two steps, for a frame loop that draws frame k + 1 while frame k is read back
  // (GlContext::startRead): submit draws the frame and starts its read-back; collect returns the
  // oldest frame submitted and not collected (valid until the next call). Where readsAhead (EGL
  // asked to, on a GL path: the cpu path's frame is whole when drawn), up to two frames may be
  // submitted before the first is collected; elsewhere each must be collected before the next is
  // submitted. Either misuse throws std::logic_error.
  void submit(const Drawing& frame, const Camera& camera, WorkerPool* pool = nullptr, const FrameLook* look = nullptr);
  const Image& collect();
  bool readsAhead() const;
  // Lets another thread draw the next frame (GlContext::releaseFromThread).
  void releaseFromThread();

  const RenderOptions& options() const;
  int samples() const;       // samples per pixel (options().msaa)
  const GlInfo& gl() const;  // the backend, device and GL renderer drawing the frames

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace particles::render
