#pragma once
// Internal to render/: a Drawing as the renderer's triangles (render/shape_mesh.hpp), seen through
// a Camera, in pixel coordinates (x right, y down from the top-left corner), with the widths of
// RenderOptions and the colours of a theme's Palette. No GL: the renderer hands the mesh to the shader
// (render/renderer.cpp); tests check it by numbers.
//
// Shapes are added back to front, in the order of core/drawing.hpp: obstacles (half-planes, then
// disks) → guides (circles, then lines) → springs → rods → bodies → trails → particles → arrows →
// cursors. Trails and arrows come from a FrameLook (render/frame_look.hpp), which every builder
// here takes, optionally: its colours, radii and widths where it has them, the theme's and the
// options' where it has none (a null or empty look draws the frame as without one, to the byte).
// A look list that is neither empty nor one per item of the drawing throws std::invalid_argument
// naming the list.

#include <vector>

#include "core/drawing.hpp"
#include "core/worker_pool.hpp"
#include "render/frame_look.hpp"
#include "render/render_options.hpp"
#include "render/shape_mesh.hpp"
#include "render/theme.hpp"
#include "render/tile_bins.hpp"

namespace particles::render {

// How far (pixels) guide lines reach past every edge of the image, so that their ends never show.
inline constexpr float kGuideOverhangPx = 8.0f;

// Replaces what `shapes` (a ShapeMesh or TileBins) holds with the frame's shapes, back to front.
// Throws std::invalid_argument when the camera's height is not positive.
void buildFrameMesh(const Drawing& frame, const Camera& camera, const RenderOptions& options, const Palette& colors,
                    ShapeSink& shapes, const FrameLook* look = nullptr);

// The same shapes as buildFrameMesh, written into `bins`' slots (TileBins::slots, one per shape
// buildFrameMesh would add, frameShapeCount of them): the long sections (springs, trails and
// particles) are built in pieces of a fixed number of items, on `pool`'s threads when it is given.
// Shape k lands in slot k whatever the thread count, so the bins are the same bytes for every count.
// `bins` must have been reset to the image's size. Returns the shapes that add something (those
// buildFrameMesh gives a TileBins as records): what the renderer's automatic choice counts.
size_t buildFrameTiles(const Drawing& frame, const Camera& camera, const RenderOptions& options, const Palette& colors,
                       TileBins& bins, WorkerPool* pool = nullptr, const FrameLook* look = nullptr);

// Where the resident path (render/resident_program.hpp) draws its springs and particles among the
// shapes of buildFrameMeshAround's mesh: vertices [0, springsEnd) before the springs by index,
// [springsEnd, particlesAt) between them and the particles (rods, bodies, trails), the rest after
// the particles (arrows, cursors).
struct MeshBreaks {
  size_t springsEnd = 0, particlesAt = 0;
};
// buildFrameMesh's shapes but the particles, and the springs by index (Drawing::springTopology),
// which the resident path draws from GL's copy of them; the frame's springs by position, if any,
// come just before those by index. The look's particle and spring colours and radii for those it
// leaves out are the resident path's to draw.
MeshBreaks buildFrameMeshAround(const Drawing& frame, const Camera& camera, const RenderOptions& options,
                                const Palette& colors, ShapeMesh& mesh, const FrameLook* look = nullptr);

// Where every path puts the frame's particles: (x, y) in pixels per particle, into `pixels`, on
// `pool`'s threads when it is given. Throws std::invalid_argument as buildFrameMesh does.
void particlePixels(const Drawing& frame, const Camera& camera, const RenderOptions& options,
                    std::vector<float>& pixels, WorkerPool* pool = nullptr);
// Pixels per world unit, and a particle's radius in pixels, as every path draws them.
double pixelsPerUnit(const Camera& camera, const RenderOptions& options);
float particleRadiusPx(const Camera& camera, const RenderOptions& options);

// How many shapes buildFrameMesh gives `frame` before any is dropped as off-screen: an upper bound
// on what a sink receives, counted without building anything (the renderer's choice of raster path).
size_t frameShapeCount(const Drawing& frame, const FrameLook* look = nullptr);

}  // namespace particles::render
