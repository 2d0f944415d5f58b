#pragma once
// Internal to render/: a Drawing as the renderer's triangles (render/shape_mesh.hpp), seen through
// a Camera, in pixel coordinates (x right, y down from the top-left corner), with the widths of
// RenderOptions and the colours of a Theme. No GL: the renderer hands the mesh to the shader
// (render/renderer.cpp); tests check it by numbers.
//
// Shapes are added back to front, in the order of core/drawing.hpp: obstacles (half-planes, then
// disks) → guides (circles, then lines) → springs → rods → bodies → particles → cursors.

#include "core/drawing.hpp"
#include "core/worker_pool.hpp"
#include "render/render_options.hpp"
#include "render/shape_mesh.hpp"
#include "render/theme.hpp"
#include "render/tile_bins.hpp"

namespace particles::render {

// How far (pixels) guide lines reach past every edge of the image, so that their ends never show.
inline constexpr float kGuideOverhangPx = 8.0f;

// Replaces what `shapes` (a ShapeMesh or TileBins) holds with the frame's shapes, back to front.
// Throws std::invalid_argument when the camera's height is not positive.
void buildFrameMesh(const Drawing& frame, const Camera& camera, const RenderOptions& options, const Theme& colors,
                    ShapeSink& shapes);

// The same shapes as buildFrameMesh, written into `bins`' slots (TileBins::slots, one per shape
// buildFrameMesh would add, frameShapeCount of them): the long sections (springs and particles)
// are built in pieces of a fixed number of items, on `pool`'s threads when it is given. Shape k
// lands in slot k whatever the thread count, so the bins are the same bytes for every count.
// `bins` must have been reset to the image's size. Returns the shapes that add something (those
// buildFrameMesh gives a TileBins as records): what the renderer's automatic choice counts.
size_t buildFrameTiles(const Drawing& frame, const Camera& camera, const RenderOptions& options, const Theme& colors,
                       TileBins& bins, WorkerPool* pool = nullptr);

// How many shapes buildFrameMesh gives `frame` before any is dropped as off-screen: an upper bound
// on what a sink receives, counted without building anything (the renderer's choice of raster path).
size_t frameShapeCount(const Drawing& frame);

}  // namespace particles::render
