#include "render/renderer.hpp"

#include "render/frame_memory.hpp"
#include "render/frame_mesh.hpp"
#include "render/gl_context.hpp"
#include "render/shader_program.hpp"
#include "render/shape_mesh.hpp"
#include "render/tile_bins.hpp"
#include "render/tile_program.hpp"

namespace particles::render {

namespace {

// Premultiplied colour (what GL leaves over a transparent background) to straight colour, in
// place: c = C · 255 / a, rounded to nearest. A pixel with alpha 0 stays (0, 0, 0, 0).
void unpremultiply(Image& image) {
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    const unsigned a = image.rgba[i + 3];
    if (a == 0 || a == 255) continue;
    for (size_t k = 0; k < 3; ++k) {
      const unsigned c = (unsigned(image.rgba[i + k]) * 255u + a / 2) / a;
      image.rgba[i + k] = std::uint8_t(c > 255u ? 255u : c);
    }
  }
}

}  // namespace

struct Renderer::Impl {
  // Members in the order they are made: the program is compiled in the context, current once made.
  RenderOptions options;
  Theme colors;
  std::unique_ptr<GlContext> context;
  ShaderProgram program;
  ShapeMesh mesh;  // the frame's triangles, storage reused from frame to frame
  TileBins bins;   // or its shapes in tiles
  std::unique_ptr<TileProgram> tiles;  // made when first needed
  Image straight;                      // a transparent frame with its colour unpremultiplied

  Impl(const RenderOptions& o, const GlRequest& gl)
      : options(o),
        colors(theme(o.themeName)),
        context(makeGlContext(gl, o.width, o.height)),
        program(context->gl(), o.msaa, o.width, o.height, context->flipsY()) {
    // Allocated now, with the frame (render/frame_memory.hpp): later copies of the frame reuse it.
    if (o.transparentBackground) straight = allocateImage(o.width, o.height, "the frame's unpremultiplied copy");
  }
};

Renderer::Renderer(const RenderOptions& options, const GlRequest& gl) {
  validate(options);
  impl_ = std::make_unique<Impl>(options, gl);
}

Renderer::~Renderer() = default;  // the context owns the program; destroying it frees both

const RenderOptions& Renderer::options() const {
  return impl_->options;
}
int Renderer::samples() const {
  return impl_->options.msaa;
}
void Renderer::releaseFromThread() { impl_->context->releaseFromThread(); }

const GlInfo& Renderer::gl() const {
  return impl_->context->info();
}

const Image& Renderer::render(const Drawing& frame, const Camera& camera, WorkerPool* pool) {
  Impl& m = *impl_;
  // automatic: a frame that cannot reach the threshold goes straight to triangles; one that may
  // is built as tiles first and decided on the shapes it really has (degenerate ones dropped).
  const size_t shapes = frameShapeCount(frame);
  bool tiled =
      m.options.raster == Raster::tiles || (m.options.raster == Raster::automatic && shapes >= kTilesFromShapes);
  if (tiled) {
    m.bins.reset(m.options.width, m.options.height);
    const size_t recorded = buildFrameTiles(frame, camera, m.options, m.colors, m.bins, pool);
    tiled = m.options.raster == Raster::tiles || recorded >= kTilesFromShapes;
  }
  const bool transparent = m.options.transparentBackground;
  m.context->beginFrame(m.colors.background, transparent);
  if (tiled) {
    m.bins.bin(pool);
    if (!m.tiles) {
      m.tiles = std::make_unique<TileProgram>(m.context->gl(), m.options.msaa, m.options.width, m.options.height,
                                              m.context->flipsY());
    }
    tiled = m.tiles->fits(m.bins);  // else too large for GL's texture buffers: triangles
  }
  if (tiled) {
    m.tiles->draw(m.bins, m.colors.background, transparent);
  } else {
    buildFrameMesh(frame, camera, m.options, m.colors, m.mesh);
    m.program.draw(m.mesh);
  }
  if (!transparent) return m.context->finishFrame();
  m.straight = m.context->finishFrame();
  unpremultiply(m.straight);
  return m.straight;
}

}  // namespace particles::render
