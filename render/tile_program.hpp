#pragma once
// Internal to render/: the tile path's full-screen pass (render/tile_bins.hpp says why it exists).
// Each pixel walks its tile's shapes: first from the front to the last one covering all its
// samples (nothing behind that one shows), then from there to the front again, blending each
// shape's covered share over the colour so far exactly as the triangle path's GL blending does in
// the 8-bit framebuffer (render/gl_context.cpp), so both paths give the same pixels up to the
// rounding of the edge distances (tests/test_render_tiles.cpp measures how close).
//
// The shapes, the tiles' (first, count) and the tiles' shape lists go to GL as texture buffers
// (GL 3.1), refilled each frame.

#include <cstddef>

#include "render/theme.hpp"
#include "render/tile_bins.hpp"

namespace particles::render {

struct GlFunctions;  // render/gl_functions.hpp

class TileProgram {
 public:
  // Compiles the pass for `samples` per pixel (render/shader_program.hpp's patterns) in the
  // current GL context, whose functions `gl` are, and makes its buffers there. Image row y is GL
  // window row y, or height − y with `flipY` (images `width` × `height` pixels). Throws RenderError with the compiler's log.
  TileProgram(const GlFunctions& gl, int samples, int width, int height, bool flipY);
  // No destructor: the program, buffers and textures are freed with their context (as ShaderProgram's).
  TileProgram(const TileProgram&) = delete;
  TileProgram& operator=(const TileProgram&) = delete;

  // Whether the frame's shapes (4 texels each) and tile lists fit GL's texture buffers here
  // (GL_MAX_TEXTURE_BUFFER_SIZE texels each); a frame that does not must take the triangle path.
  bool fits(const TileBins& bins) const;

  // Draws the frame's shapes over `background` in the current context, every pixel of the tiles
  // that have shapes written whole; the other pixels keep what the frame was cleared to (the
  // same background). With `transparent`, over nothing instead: colour premultiplied by alpha, as
  // the triangle path leaves it (GlContext::beginFrame). `bins` must have been binned for this
  // image size.
  void draw(const TileBins& bins, Rgb background, bool transparent) const;

 private:
  const GlFunctions& gl_;
  unsigned program_ = 0;
  int positionAttr_ = -1;
  unsigned buffers_[3] = {0, 0, 0};   // shapes, tiles, items
  unsigned textures_[3] = {0, 0, 0};  // their texture buffers
  mutable size_t capacity_[3] = {0, 0, 0};  // bytes each buffer's store holds
  int backgroundUniform_ = -1, backgroundAlphaUniform_ = -1, tilesPerRowUniform_ = -1;
  long long maxTexels_ = 0;  // GL_MAX_TEXTURE_BUFFER_SIZE
};

}  // namespace particles::render
