#pragma once
// Internal to render/: a frame's shapes for the tile path (render/tile_program.hpp). Drawing a
// primitive costs llvmpipe a fixed time in its front end whatever it covers (bench/README.md, "Measurements behind choices in the source"), so a frame
// of 100,000 particles and 200,000 springs (1.2 million triangles) cannot be drawn shape by shape at
// video rates. Instead each shape becomes one record of its true boundary (the same edges and radii the
// triangle path's vertices carry, render/shape_mesh.hpp), the records are sorted into screen
// tiles on the CPU (linear in the shapes and the tiles they touch), and one full-screen pass tests
// each pixel's samples against its tile's shapes in painter's order.
//
// A record is 4 texels of 4 floats (ShapeRecord, 64 bytes), in pixel coordinates (x right, y
// down). A convex shape's edge e has the signed distance d_e(p) = a_e·x + b_e·y + c_e, positive
// inside; an absent 4th edge is 0·x + 0·y + kFarPx.
//   convex:  texel 0 = (a_0 … a_3), texel 1 = (b_0 … b_3), texel 2 = (c_0 … c_3),
//            texel 3 = (colour, smoothed edges (bit e), 0, 0)
//   annulus: texel 0 = (centre x, centre y, outer radius, inner radius), texels 1 and 2 zero,
//            texel 3 = (colour, 16, 0, 0)
// A colour is r + 256 g + 65536 b, a whole number below 2^24: exact in a float.
inline constexpr float kAnnulusKind = 16.0f;

#include <cstdint>
#include <vector>

#include "render/shape_mesh.hpp"

namespace particles::render {

// Pixels per tile side: 4 drew the cloth at 316 × 316 fastest (2 and 8 were slower: longer lists
// to walk per pixel against more tiles to bin, bench/README.md).
inline constexpr int kTileSizePx = 4;

struct ShapeRecord {
  float texel[4][4];
};

class TileBins final : public ShapeSink {
 public:
  using ShapeSink::convex;

  // Forgets the shapes and sets the image size (pixels, both > 0).
  void reset(int width, int height);
  // Makes room for `shapes` shapes at once (render/frame_mesh.hpp's frameShapeCount): grown by
  // push_back, the records of a million-particle cloth's 3 million shapes (192 MB) took a 268 MB
  // store, and their tile ranges another 19 MB more than they need (issue 28).
  void reserve(size_t shapes);
  void clear() override;

  void convex(std::span<const P2> corners, Rgb col, unsigned smoothEdges = 0xF) override;
  void annulus(P2 c, float inner, float outer, Rgb col) override;
  // Records a line directly: its edges are known without convexEdges' square root per edge.
  void line(P2 a, P2 b, float width, Rgb col, bool squareCaps = false) override;

  // Sorts the shapes into tiles: after this, tile t's shapes are items()[first .. first + count)
  // with (first, count) = tiles()[2t], tiles()[2t + 1], in the order they were added. Tiles are
  // numbered row by row from the top-left; a tile lists each shape that may cover one of its
  // pixels (a shape's grown box, less tiles wholly outside one of its edges or its ring), from
  // the last shape that covers all of it, if one does.
  void bin();

  int width() const { return width_; }
  int height() const { return height_; }
  int tilesPerRow() const { return tilesX_; }
  int tileRows() const { return tilesY_; }
  const std::vector<ShapeRecord>& shapes() const { return shapes_; }
  const std::vector<std::uint32_t>& tiles() const { return tiles_; }
  const std::vector<std::uint32_t>& items() const { return items_; }
  // The tiles with shapes as rectangles for the pass to draw: each run of such tiles along a row
  // of tiles is two triangles, 6 corners (x, y) in image pixels, clipped to the image.
  const std::vector<float>& runs() const { return runs_; }

 private:
  // A shape's tiles: an inclusive range of tile columns and rows, and the test that drops tiles of
  // that range the shape cannot reach.
  struct Reach {
    int tx0, ty0, tx1, ty1;
  };
  void addReach(float x0, float y0, float x1, float y1);
  bool reachesTile(size_t shape, int tx, int ty) const;
  // Calls visit(tile, shape) for each tile each shape reaches, shape by shape in the order they
  // were added, each shape's tiles row by row.
  template <typename Visit>
  void forEachReachedTile(Visit&& visit) const;
  bool coversTile(size_t shape, int tx, int ty) const;

  int width_ = 0, height_ = 0, tilesX_ = 0, tilesY_ = 0;
  std::vector<ShapeRecord> shapes_;
  std::vector<Reach> reach_;  // per shape
  std::vector<std::uint32_t> tiles_, items_;
  std::vector<float> runs_;
  std::vector<std::uint32_t> scratch_;
};

}  // namespace particles::render
