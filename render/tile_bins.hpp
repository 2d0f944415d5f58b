#pragma once
// Internal to render/: a frame's shapes for the tile path (render/tile_program.hpp). Drawing a
// primitive costs llvmpipe a fixed time in its front end whatever it covers (bench/README.md, "Tile path"), so a frame
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
//            texel 3 = (colour, smoothed edges (bit e), alpha, 0)
//   annulus: texel 0 = (centre x, centre y, outer radius, inner radius), texels 1 and 2 zero,
//            texel 3 = (colour, 16, alpha, 0)
// A colour is r + 256 g + 65536 b, a whole number below 2^24: exact in a float. Alpha is the
// colour's straight alpha, 0 … 255 (255 opaque): the covered share n / S of a pixel's S samples
// becomes floor(n · alpha / S + 0.5) / 255, which for 255 is the share rounded to 8 bits as before
// alpha was recorded, in the same float operations (render/tile_composite.cpp, tile_program.cpp).
inline constexpr float kAnnulusKind = 16.0f;

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/worker_pool.hpp"
#include "render/shape_mesh.hpp"

namespace particles::render {

// Pixels per tile side: 4 drew the cloth at 316 × 316 fastest (2 and 8 were slower: longer lists
// to walk per pixel against more tiles to bin: bench/README.md, "Measurements behind choices in the
// source").
inline constexpr int kTileSizePx = 4;

struct ShapeRecord {
  float texel[4][4];
};

// An allocator whose resize leaves new elements uninitialised (default-initialised): a frame's
// records and tile ranges are all written before they are read, and zeroing a million-particle
// frame's 190 MB of records first would cost as much as writing them.
template <typename T>
struct UninitialisedAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <typename U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <typename T>
using UninitialisedVector = std::vector<T, UninitialisedAllocator<T>>;

class TileBins final : public ShapeSink {
 public:
  using ShapeSink::convex;

  // Forgets the shapes and sets the image size (pixels, both > 0).
  void reset(int width, int height);
  void clear() override;

  void convex(std::span<const P2> corners, Rgba col, unsigned smoothEdges = 0xF) override;
  void annulus(P2 c, float inner, float outer, Rgba col) override;
  // Records a line directly: its edges are known without convexEdges' square root per edge.
  void line(P2 a, P2 b, float width, Rgba col, bool squareCaps = false) override;

  // Shapes written into numbered places, for building a frame's records on several threads
  // (render/frame_mesh.hpp's buildFrameTiles): slots(n) makes the records 0 … n − 1, to be filled
  // by writers; writer(k) is a ShapeSink that fills slots k, k + 1, … one per shape it is given.
  // A shape that would add nothing (a degenerate line or polygon, which convex() and line() drop)
  // takes its slot all the same, as an empty record that no tile lists: so which slot a shape
  // lands in depends only on the shapes before it, never on how the work was split, and the
  // frame's bins are the same whatever the thread count. Slots must all be written before bin().
  // The records are made at once, frameShapeCount of them: grown by push_back, the records of a
  // million-particle cloth's 3 million shapes (192 MB) took a 268 MB store, and their tile ranges
  // another 19 MB more than they need.
  class SlotWriter;
  void slots(size_t shapes);
  SlotWriter writer(size_t firstSlot);

  // Sorts the shapes into tiles: after this, tile t's shapes are items()[first .. first + count)
  // with (first, count) = tiles()[2t], tiles()[2t + 1], in the order they were added. Tiles are
  // numbered row by row from the top-left; a tile lists each shape that may cover one of its
  // pixels (a shape's grown box, less tiles wholly outside one of its edges or its ring), from
  // the last opaque shape (alpha 255) that covers all of it, if one does. With a pool, the work is shared out in
  // bands of tile rows (and the shapes in fixed chunks): the same lists as without one.
  void bin(WorkerPool* pool = nullptr);

  int width() const { return width_; }
  int height() const { return height_; }
  int tilesPerRow() const { return tilesX_; }
  int tileRows() const { return tilesY_; }
  const UninitialisedVector<ShapeRecord>& shapes() const { return shapes_; }
  const UninitialisedVector<std::uint32_t>& tiles() const { return tiles_; }
  const UninitialisedVector<std::uint32_t>& items() const { return items_; }
  // The tiles with shapes as rectangles for the pass to draw: each run of such tiles along a row
  // of tiles is two triangles, 6 corners (x, y) in image pixels, clipped to the image.
  const std::vector<float>& runs() const { return runs_; }

 private:
  // A shape's tiles: an inclusive range of tile columns and rows, and the test that drops tiles of
  // that range the shape cannot reach.
  struct Reach {
    int tx0, ty0, tx1, ty1;  // tx1 < tx0: none
  };
  static constexpr Reach kNoReach = {0, 0, -1, -1};
  // A shape's record and reach, false for a shape that adds nothing.
  bool convexShape(std::span<const P2> corners, Rgba col, unsigned smoothEdges, ShapeRecord& r, Reach& q) const;
  bool lineShape(P2 a, P2 b, float width, Rgba col, bool squareCaps, ShapeRecord& r, Reach& q) const;
  void annulusShape(P2 c, float inner, float outer, Rgba col, ShapeRecord& r, Reach& q) const;
  Reach reachOf(float x0, float y0, float x1, float y1) const;
  bool reachesTile(size_t shape, int tx, int ty) const;
  // Calls visit(tile) for each tile of rows [rowBegin, rowEnd) that `shape` reaches, row by row.
  template <typename Visit>
  void forEachReachedTile(std::uint32_t shape, int rowBegin, int rowEnd, Visit&& visit) const;
  bool coversTile(size_t shape, int tx, int ty) const;
  float thickness(size_t shape) const;
  // bin()'s stages: the shapes sorted by band of tile rows (bandShapes_, bandFirst_); each band's
  // tiles counted, then given their shapes (tiles_, items_, coverFrom_); the runs of tiles with shapes.
  void sortIntoBands(WorkerPool* pool, size_t bands);
  void fillTiles(WorkerPool* pool, size_t bands);
  void collectRuns();

  int width_ = 0, height_ = 0, tilesX_ = 0, tilesY_ = 0;
  UninitialisedVector<ShapeRecord> shapes_;
  UninitialisedVector<Reach> reach_;  // per shape
  UninitialisedVector<std::uint32_t> tiles_, items_;
  std::vector<float> runs_;
  // bin()'s scratch, kept from frame to frame: the shapes of each band of tile rows, band after
  // band (bandFirst_[b] … bandFirst_[b + 1]), and the counts per chunk of shapes and band.
  UninitialisedVector<std::uint32_t> bandShapes_, chunkBandCounts_;
  UninitialisedVector<std::uint32_t> coverFrom_;  // per tile: where its list will start
  std::vector<size_t> bandFirst_;
};

// Fills a TileBins' slots from one on (TileBins::writer): one slot per shape. clear() goes back
// to the first slot.
class TileBins::SlotWriter final : public ShapeSink {
 public:
  using ShapeSink::convex;
  void clear() override { next_ = first_; }
  void convex(std::span<const P2> corners, Rgba col, unsigned smoothEdges = 0xF) override;
  void annulus(P2 c, float inner, float outer, Rgba col) override;
  void line(P2 a, P2 b, float width, Rgba col, bool squareCaps = false) override;
  size_t next() const { return next_; }          // the slot the next shape fills
  size_t recorded() const { return recorded_; }  // shapes written that add something

 private:
  friend class TileBins;
  SlotWriter(TileBins& bins, size_t first) : bins_(bins), first_(first), next_(first) {}
  void put(bool valid, const ShapeRecord& r, const Reach& q);
  TileBins& bins_;
  size_t first_, next_, recorded_ = 0;
};

}  // namespace particles::render
