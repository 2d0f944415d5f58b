#pragma once
// Internal to render/: a frame's shapes as triangles for the renderer's coverage shader
// (render/shader_program.cpp). Each vertex carries its shape's true boundary, so the fragment
// shader can test every sample of a pixel against it (multisampling in the shader,
// render/renderer.hpp).
// Every primitive's triangles reach kFringePx past its smoothed edges, so that each pixel with a
// sample inside gets a fragment; the shader discards those no sample covers.

#include <array>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

#include "render/theme.hpp"

namespace particles::render {

using P2 = std::array<float, 2>;  // a point in pixels, x right, y down from the top-left corner

// How far (pixels) every anti-aliased edge is pushed outwards, so that a pixel whose centre lies
// just outside a shape but one of whose samples lies inside still gets a fragment. Samples sit at
// most 0.5 px from the centre along each axis (0.71 px away), so 1 px is enough.
inline constexpr float kFringePx = 1.0f;
// A distance that never limits coverage: the slot of an edge that is not anti-aliased or absent.
inline constexpr float kFarPx = 1.0e4f;

// One vertex as the shader sees it (interleaved). `shape` says where the primitive's true
// boundary is:
//   kind 0 (edges):  shape = signed distances in pixels to up to four edges, positive inside;
//                    distances are affine in position, so interpolation and dFdx/dFdy are exact.
//   kind 1 (circle): shape = (x, y) offset from the centre in pixels, outer radius, inner radius;
//                    a sample is covered when inner ≤ |offset + sample| ≤ outer.
struct ShapeVertex {
  float x, y;
  float shape[4];
  float kind;
  std::uint8_t rgba[4];  // straight alpha: the shader multiplies the covered share by rgba[3] / 255
};

// The shapes of a frame in painter's order, as the frame's builder (render/frame_mesh.hpp) adds
// them. Every shape is a convex polygon or an annulus of one colour with straight alpha (Rgba): the
// share of a pixel it covers is multiplied by a / 255 on every path. Two sinks take them: ShapeMesh (triangles for
// the per-primitive path) and TileBins (records binned into screen tiles for the tile path,
// render/tile_bins.hpp).
class ShapeSink {
 public:
  virtual ~ShapeSink() = default;

  // Forgets every shape (storage is kept for the next frame).
  virtual void clear() = 0;

  // A convex polygon of 3 or 4 corners (either winding). Edge i runs from corner i to corner
  // i + 1; bit i of `smoothEdges` anti-aliases it. An edge left out is shared with a neighbouring
  // piece of the same shape: not pushed out and not tested, so the pieces tile without a seam.
  virtual void convex(std::span<const P2> corners, Rgba col, unsigned smoothEdges = 0xF) = 0;
  void convex(std::initializer_list<P2> corners, Rgba col, unsigned smoothEdges = 0xF) {
    convex(std::span<const P2>(corners.begin(), corners.size()), col, smoothEdges);
  }
  // A segment of the given pixel width; squareCaps extends it by half the width at both ends.
  virtual void line(P2 a, P2 b, float width, Rgba col, bool squareCaps = false);
  void closedOutline(std::span<const P2> pts, float width, Rgba col);
  void disc(P2 c, float r, Rgba col) { annulus(c, 0.0f, r, col); }
  void ring(P2 c, float r, float width, Rgba col);
  // The points between radii `inner` and `outer` (inner 0: a disc).
  virtual void annulus(P2 c, float inner, float outer, Rgba col) = 0;
};

// A convex polygon's edges, as both sinks need them: unit normals pointing inside, how far each
// edge is pushed out (kFringePx when smoothed, else 0), and the corners of the polygon grown by
// those pushes. `valid` is false for a degenerate polygon (an edge shorter than 1e-4 px), which is
// not drawn.
struct ConvexEdges {
  size_t count = 0;
  std::array<P2, 4> normal{};
  std::array<float, 4> push{};
  std::array<P2, 4> grown{};
  bool valid = false;
};
// Throws std::logic_error unless there are 3 or 4 corners.
ConvexEdges convexEdges(std::span<const P2> corners, unsigned smoothEdges);

// Triangles in pixel coordinates, drawn in the order the shapes are added (painter's order).
class ShapeMesh final : public ShapeSink {
 public:
  using ShapeSink::convex;
  void clear() override { vertices_.clear(); }
  const std::vector<ShapeVertex>& vertices() const { return vertices_; }

  void convex(std::span<const P2> corners, Rgba col, unsigned smoothEdges = 0xF) override;
  void annulus(P2 c, float inner, float outer, Rgba col) override;

 private:
  std::vector<ShapeVertex> vertices_;
};

}  // namespace particles::render
