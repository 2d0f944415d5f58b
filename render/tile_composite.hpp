#pragma once
// Internal to render/: the tile path's pass (render/tile_program.hpp) done by the program's own
// threads instead of GL: the `cpu` raster path (render/render_options.hpp). Each 4 × 4 px tile's
// listed shapes are tested at every sample of its 16 pixels, four pixels (one row of the tile) at a
// time in one vector, and blended front to back over the background as the tile pass's fragment
// shader does, from the same records (render/tile_bins.hpp) and with the same formulas. The image is
// written directly: no GL draw and no read-back, and no clear (a tile without shapes is set to the
// background only where the image's previous frame had shapes in it). Why: llvmpipe pays a fixed
// cost per triangle and per 4 × 4 block a triangle crosses, and its clear and read-back pass over
// the whole frame twice; the demo's frame costs less than half as much this way (bench/README.md,
// "The cpu raster").
//
// Rounding: the edge distances are the shader's, d = c + a·x + b·y at the pixel centre, and a
// sample is inside an edge when d is at least minus that edge's offset at the sample (exactly the
// shader's d + offset ≥ 0, in one comparison). A sample exactly on an edge is inside only for a top
// or left edge, GL's rasterisation rule, where the GL tile pass counts every such tie in (and its
// compiler may fuse its multiplications and additions): both paths agree within the goldens'
// tolerances (tests/test_render_cpu.cpp measures how closely), not bit for bit. A shape's alpha
// scales its covered share before that share is rounded to 8 bits, as the triangle path's
// framebuffer takes its fragments' alpha; the blends after it are in float and rounded once, where
// the triangle path rounds after each (tests/test_render_frame_look.cpp measures translucent
// shapes). The arithmetic does not depend on the thread count or on which thread draws a tile: the
// same bytes for every count.

#include <cstdint>
#include <vector>

#include "core/worker_pool.hpp"
#include "render/image.hpp"
#include "render/theme.hpp"
#include "render/tile_bins.hpp"

namespace particles::render {

// An image compositeTiles draws into, and what it knows of the image's content: which tiles hold
// more than the background (a frame's tiles without shapes keep the background from an earlier
// frame, and only those that held shapes then are set to it again), over which background. Empty
// tilesDrawn (a frame made anew, or an image someone else wrote: clear it) rewrites every tile.
struct CompositedFrame {
  Image image;
  std::vector<std::uint8_t> tilesDrawn;  // per tile, row by row: 1 where it may hold shapes
  Rgb background{};
  bool transparent = false;
};

// Draws `bins`' shapes (binned, TileBins::bin) over `background` into `frame`'s image, which must
// have the bins' size, at `samples` per pixel (one of kSampleCounts, render/render_options.hpp):
// afterwards every pixel is the frame's. With `transparent`, over nothing instead: the colour
// premultiplied by alpha, as the GL paths leave it (the renderer makes it straight). With a pool,
// bands of tile rows are drawn on its threads. Throws std::invalid_argument for a sample count
// without a pattern or an image of another size.
void compositeTiles(const TileBins& bins, int samples, Rgb background, bool transparent, CompositedFrame& frame,
                    WorkerPool* pool = nullptr);

}  // namespace particles::render
