#include "render/renderer.hpp"

#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "render/frame_memory.hpp"
#include "render/frame_mesh.hpp"
#include "render/gl_context.hpp"
#include "render/resident_program.hpp"
#include "render/shader_program.hpp"
#include "render/shape_mesh.hpp"
#include "render/tile_bins.hpp"
#include "render/tile_composite.hpp"
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

// What Renderer::gl says on the cpu path, which makes no GL context.
const GlInfo kNoGl = [] {
  GlInfo none;
  none.made = false;
  return none;
}();

}  // namespace

struct Renderer::Impl {
  // Members in the order they are made: the program is compiled in the context, current once made.
  RenderOptions options;
  Palette colors;
  // The path every frame is drawn on: the options' raster path and the GPU request decide it
  // (rasterTaken), once for the renderer. On the cpu path the image is made at the first frame and
  // is ready when drawn, so the renderer does not read ahead; and it needs no GL context: none is
  // made, so Mesa's driver is not loaded nor llvmpipe's threads started, and it draws where GL
  // cannot start.
  const Raster taken;
  std::unique_ptr<GlContext> context;    // none on the cpu path
  std::optional<ShaderProgram> program;  // with the context
  ShapeMesh mesh;  // the frame's triangles, storage reused from frame to frame
  TileBins bins;   // or its shapes in tiles
  std::unique_ptr<TileProgram> tiles;  // made when first needed
  std::unique_ptr<ResidentProgram> resident;  // on the resident path
  std::vector<float> pixels;                  // its particles' positions in pixels
  Image straight;                             // a transparent frame with its colour unpremultiplied
  CompositedFrame composited;
  int submitted = 0;  // frames submitted and not yet collected

  Impl(const RenderOptions& o, const GlRequest& gl)
      : options(o), colors(theme(o.themeName)), taken(rasterTaken(o.raster, gl.gpu)) {
    if (onCpu()) {
      // The request is still checked, so that a bad one fails alike on every path.
      validate(gl);
      if (gl.gpu) {
        throw std::invalid_argument(
            "the cpu raster draws without GL, so it cannot use the GPU asked for: drop the GPU request, or choose "
            "the resident, tiles or triangles raster");
      }
    } else {
      context = makeGlContext(gl, o.width, o.height);
      program.emplace(context->gl(), o.msaa, o.width, o.height, context->flipsY());
    }
    // Allocated now, with the frame (render/frame_memory.hpp): later copies of the frame reuse it.
    if (o.transparentBackground) straight = allocateImage(o.width, o.height, "the frame's unpremultiplied copy");
  }

  // The frame on the resident path: the CPU's shapes before the springs, the springs by index
  // from GL's copy, the CPU's shapes between, the particles from GL's copy, the CPU's shapes after.
  void drawResident(const Drawing& frame, const Camera& camera, WorkerPool* pool, const FrameLook* look) {
    // Checks the topology and the look's lengths.
    const MeshBreaks breaks = buildFrameMeshAround(frame, camera, options, colors, mesh, look);
    particlePixels(frame, camera, options, pixels, pool);
    resident->upload(pixels, frame.particleFixed, frame.springTopology);
    if (look) {
      // The springs by position are the mesh's; GL's are those by index, after them.
      std::span<const Rgba> springColors = look->springColors;
      if (!springColors.empty()) springColors = springColors.subspan(frame.springs.size());
      resident->uploadLook(look->particleColors, look->particleRadiiPx, springColors);
    } else {
      resident->uploadLook({}, {}, {});
    }
    const ResidentLook themed{.particleRadiusPx = particleRadiusPx(camera, options),
                              .springWidthPx = float(options.springWidthPx),
                              .pixelsPerUnit = pixelsPerUnit(camera, options),
                              .strainForFullColor = options.strainForFullColor,
                              .colors = colors};
    program->draw(mesh, 0, breaks.springsEnd);
    resident->drawSprings(themed);
    program->draw(mesh, breaks.springsEnd, breaks.particlesAt);
    resident->drawParticles(themed);
    program->draw(mesh, breaks.particlesAt, mesh.vertices().size());
  }

  bool onCpu() const { return taken == Raster::cpu; }

  // The frame on the cpu path: its shapes' records built and binned on the pool, then composited.
  void drawCpu(const Drawing& frame, const Camera& camera, WorkerPool* pool, const FrameLook* look) {
    if (composited.image.rgba.empty()) composited.image = allocateImage(options.width, options.height, "the frame");
    bins.reset(options.width, options.height);
    buildFrameTiles(frame, camera, options, colors, bins, pool, look);
    bins.bin(pool);
    compositeTiles(bins, options.msaa, colors.background, options.transparentBackground, composited, pool);
  }

  // The frame built on the CPU: as triangles, or as tiles (the automatic choice, RenderOptions).
  void drawBuilt(const Drawing& frame, const Camera& camera, WorkerPool* pool, const FrameLook* look) {
    // automatic (here when the resident path could not take the frame): a frame that cannot reach
    // the threshold goes straight to triangles; one that may is built as tiles first and decided
    // on the shapes it really has (degenerate ones dropped).
    const size_t shapes = frameShapeCount(frame, look);
    bool tiled = options.raster == Raster::tiles ||
                 (options.raster != Raster::triangles && shapes >= kTilesFromShapes);
    if (tiled) {
      bins.reset(options.width, options.height);
      const size_t recorded = buildFrameTiles(frame, camera, options, colors, bins, pool, look);
      tiled = options.raster == Raster::tiles || recorded >= kTilesFromShapes;
    }
    const bool transparent = options.transparentBackground;
    context->beginFrame(colors.background, transparent);
    if (tiled) {
      bins.bin(pool);
      if (!tiles) {
        tiles = std::make_unique<TileProgram>(context->gl(), options.msaa, options.width, options.height,
                                                context->flipsY());
      }
      tiled = tiles->fits(bins);  // else too large for GL's texture buffers: triangles
    }
    if (tiled) {
      tiles->draw(bins, colors.background, transparent);
    } else {
      buildFrameMesh(frame, camera, options, colors, mesh, look);
      program->draw(mesh);
    }
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
void Renderer::releaseFromThread() {
  if (impl_->context) impl_->context->releaseFromThread();
}

const GlInfo& Renderer::gl() const {
  return impl_->context ? impl_->context->info() : kNoGl;
}

void Renderer::submit(const Drawing& frame, const Camera& camera, WorkerPool* pool, const FrameLook* look) {
  Impl& m = *impl_;
  if (look && look->empty()) look = nullptr;  // as without one, to the byte
  if (m.submitted >= (readsAhead() ? 2 : 1)) throw std::logic_error("Renderer::submit: a frame must be collected first");
  // cpu: asked for, or automatic without a GPU, where it costs less than llvmpipe drawing the same
  // frame (bench/README.md, "The cpu raster"); resident: asked for, or automatic with a GPU (what
  // the path is for).
  if (m.onCpu()) {
    m.drawCpu(frame, camera, pool, look);
    ++m.submitted;
    return;
  }
  const bool transparent = m.options.transparentBackground;
  bool resident = m.taken == Raster::resident;
  if (resident) {
    m.context->beginFrame(m.colors.background, transparent);  // current, for a program made now
    if (!m.resident) {
      m.resident = std::make_unique<ResidentProgram>(m.context->gl(), m.options.msaa, m.options.width,
                                                     m.options.height, m.context->flipsY());
    }
    resident = m.resident->fits(frame.particles.size(), frame.springsByIndex());  // else built on the CPU
  }
  if (resident) {
    m.drawResident(frame, camera, pool, look);
  } else {
    m.drawBuilt(frame, camera, pool, look);
  }
  m.context->startRead();
  ++m.submitted;
}

const Image& Renderer::collect() {
  Impl& m = *impl_;
  if (m.submitted == 0) throw std::logic_error("Renderer::collect: no frame was submitted");
  --m.submitted;
  const Image& image = m.onCpu() ? m.composited.image : m.context->collectFrame();
  if (!m.options.transparentBackground) return image;
  m.straight = image;
  unpremultiply(m.straight);
  return m.straight;
}

bool Renderer::readsAhead() const {
  return !impl_->onCpu() && impl_->context->readsAhead();
}

const Image& Renderer::render(const Drawing& frame, const Camera& camera, WorkerPool* pool, const FrameLook* look) {
  submit(frame, camera, pool, look);
  return collect();
}

}  // namespace particles::render
