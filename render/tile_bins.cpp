#include "render/tile_bins.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>

namespace particles::render {

namespace {

float colorCode(Rgba col) {
  return float(col.r) + 256.0f * float(col.g) + 65536.0f * float(col.b);
}

int clampTile(float pixel, int tiles) {
  if (!(pixel >= 0.0f)) return 0;  // also NaN
  return std::min(int(pixel) / kTileSizePx, tiles - 1);
}

// Shapes smaller than this many tiles take every tile of their box: testing would cost more than
// the few pixels it saves.
constexpr int kTestedReach = 4;

}  // namespace

void TileBins::reset(int width, int height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("TileBins: the image needs a positive size");
  width_ = width;
  height_ = height;
  tilesX_ = (width + kTileSizePx - 1) / kTileSizePx;
  tilesY_ = (height + kTileSizePx - 1) / kTileSizePx;
  clear();
}

void TileBins::clear() {
  shapes_.clear();
  reach_.clear();
}

void TileBins::slots(size_t shapes) {
  shapes_.resize(shapes);  // uninitialised: every slot is written by a writer
  reach_.resize(shapes);
}

TileBins::SlotWriter TileBins::writer(size_t firstSlot) {
  return SlotWriter(*this, firstSlot);
}

// A pixel gets a shape's colour only if its centre lies in the shape grown by kFringePx (the
// triangle path's rule), so the box of the grown shape bounds its tiles; a box wholly off the
// image adds nothing (its shape still has a record, never listed).
TileBins::Reach TileBins::reachOf(float x0, float y0, float x1, float y1) const {
  if (!(x1 >= 0.0f && y1 >= 0.0f && x0 <= float(width_) && y0 <= float(height_))) return kNoReach;
  return {clampTile(x0, tilesX_), clampTile(y0, tilesY_), clampTile(x1, tilesX_), clampTile(y1, tilesY_)};
}

bool TileBins::convexShape(std::span<const P2> corners, Rgba col, unsigned smoothEdges, ShapeRecord& r,
                           Reach& q) const {
  const ConvexEdges e = convexEdges(corners, smoothEdges);
  if (!e.valid) return false;
  r = ShapeRecord{};
  for (size_t k = 0; k < 4; ++k) {
    if (k < e.count) {
      const P2 n = e.normal[k];
      r.texel[0][k] = n[0];
      r.texel[1][k] = n[1];
      r.texel[2][k] = -(n[0] * corners[k][0] + n[1] * corners[k][1]);
    } else {
      r.texel[2][k] = kFarPx;
    }
  }
  r.texel[3][0] = colorCode(col);
  r.texel[3][2] = float(col.a);
  r.texel[3][1] = float(smoothEdges & ((1u << e.count) - 1u));
  float x0 = e.grown[0][0], x1 = x0, y0 = e.grown[0][1], y1 = y0;
  for (size_t i = 1; i < e.count; ++i) {
    x0 = std::min(x0, e.grown[i][0]), x1 = std::max(x1, e.grown[i][0]);
    y0 = std::min(y0, e.grown[i][1]), y1 = std::max(y1, e.grown[i][1]);
  }
  q = reachOf(x0, y0, x1, y1);
  return true;
}

// The rectangle ShapeSink::line makes, corners a + n, b + n, b − n, a − n, every edge smoothed.
bool TileBins::lineShape(P2 a, P2 b, float width, Rgba col, bool squareCaps, ShapeRecord& r, Reach& q) const {
  float dx = b[0] - a[0], dy = b[1] - a[1];
  const float len = std::sqrt(dx * dx + dy * dy);
  if (!(len > 1e-4f)) return false;
  dx /= len;
  dy /= len;
  const float h = 0.5f * width;
  if (squareCaps) {
    a = {a[0] - dx * h, a[1] - dy * h};
    b = {b[0] + dx * h, b[1] + dy * h};
  }
  const float nx = -dy * h, ny = dx * h;
  const P2 corner[4] = {{a[0] + nx, a[1] + ny}, {b[0] + nx, b[1] + ny}, {b[0] - nx, b[1] - ny}, {a[0] - nx, a[1] - ny}};
  const P2 inward[4] = {{dy, -dx}, {-dx, -dy}, {-dy, dx}, {dx, dy}};
  r = ShapeRecord{};
  for (int k = 0; k < 4; ++k) {
    r.texel[0][k] = inward[k][0];
    r.texel[1][k] = inward[k][1];
    r.texel[2][k] = -(inward[k][0] * corner[k][0] + inward[k][1] * corner[k][1]);
  }
  r.texel[3][0] = colorCode(col);
  r.texel[3][2] = float(col.a);
  r.texel[3][1] = 15.0f;
  // The grown rectangle's corners lie within kFringePx·√2 of the rectangle's.
  const float grow = 1.5f * kFringePx;
  q = reachOf(std::min({corner[0][0], corner[1][0], corner[2][0], corner[3][0]}) - grow,
              std::min({corner[0][1], corner[1][1], corner[2][1], corner[3][1]}) - grow,
              std::max({corner[0][0], corner[1][0], corner[2][0], corner[3][0]}) + grow,
              std::max({corner[0][1], corner[1][1], corner[2][1], corner[3][1]}) + grow);
  return true;
}

void TileBins::annulusShape(P2 c, float inner, float outer, Rgba col, ShapeRecord& r, Reach& q) const {
  r = ShapeRecord{};
  r.texel[0][0] = c[0];
  r.texel[0][1] = c[1];
  r.texel[0][2] = outer;
  r.texel[0][3] = inner;
  r.texel[3][0] = colorCode(col);
  r.texel[3][2] = float(col.a);
  r.texel[3][1] = kAnnulusKind;
  const float reach = outer + kFringePx;
  q = reachOf(c[0] - reach, c[1] - reach, c[0] + reach, c[1] + reach);
}

void TileBins::convex(std::span<const P2> corners, Rgba col, unsigned smoothEdges) {
  ShapeRecord r;
  Reach q;
  if (!convexShape(corners, col, smoothEdges, r, q)) return;
  shapes_.push_back(r);
  reach_.push_back(q);
}

void TileBins::line(P2 a, P2 b, float width, Rgba col, bool squareCaps) {
  ShapeRecord r;
  Reach q;
  if (!lineShape(a, b, width, col, squareCaps, r, q)) return;
  shapes_.push_back(r);
  reach_.push_back(q);
}

void TileBins::annulus(P2 c, float inner, float outer, Rgba col) {
  ShapeRecord r;
  Reach q;
  annulusShape(c, inner, outer, col, r, q);
  shapes_.push_back(r);
  reach_.push_back(q);
}

void TileBins::SlotWriter::put(bool valid, const ShapeRecord& r, const Reach& q) {
  if (next_ >= bins_.shapes_.size()) throw std::logic_error("TileBins: a shape beyond the slots made for the frame");
  if (valid) {
    bins_.shapes_[next_] = r;
    bins_.reach_[next_] = q;
    ++recorded_;
  } else {
    bins_.shapes_[next_] = ShapeRecord{};
    bins_.reach_[next_] = kNoReach;
  }
  ++next_;
}

void TileBins::SlotWriter::convex(std::span<const P2> corners, Rgba col, unsigned smoothEdges) {
  ShapeRecord r;
  Reach q;
  const bool valid = bins_.convexShape(corners, col, smoothEdges, r, q);
  put(valid, r, q);
}

void TileBins::SlotWriter::line(P2 a, P2 b, float width, Rgba col, bool squareCaps) {
  ShapeRecord r;
  Reach q;
  const bool valid = bins_.lineShape(a, b, width, col, squareCaps, r, q);
  put(valid, r, q);
}

void TileBins::SlotWriter::annulus(P2 c, float inner, float outer, Rgba col) {
  ShapeRecord r;
  Reach q;
  bins_.annulusShape(c, inner, outer, col, r, q);
  put(true, r, q);
}

// Whether the shape covers every sample of every pixel of the tile: samples lie within ±0.5 px of
// their pixel's centre (samplePattern), so it must contain the tile grown by half a pixel. Corners
// suffice for a convex shape; an annulus needs the farthest corner inside its outer circle and the
// nearest point outside its inner one. A shape with alpha below 255 hides nothing: what lies
// behind shows through it.
bool TileBins::coversTile(size_t shape, int tx, int ty) const {
  const ShapeRecord& r = shapes_[shape];
  if (r.texel[3][2] != 255.0f) return false;
  constexpr float kSampleReach = 0.5f + 1e-3f;
  const float loX = float(tx * kTileSizePx) + 0.5f - kSampleReach;
  const float hiX = float(std::min((tx + 1) * kTileSizePx, width_)) - 0.5f + kSampleReach;
  const float loY = float(ty * kTileSizePx) + 0.5f - kSampleReach;
  const float hiY = float(std::min((ty + 1) * kTileSizePx, height_)) - 0.5f + kSampleReach;
  if (r.texel[3][1] == kAnnulusKind) {
    const float cx = r.texel[0][0], cy = r.texel[0][1], outer = r.texel[0][2], inner = r.texel[0][3];
    const float fx = std::max(std::abs(loX - cx), std::abs(hiX - cx));
    const float fy = std::max(std::abs(loY - cy), std::abs(hiY - cy));
    if (fx * fx + fy * fy > outer * outer) return false;
    if (!(inner > 0.0f)) return true;
    const float nx = std::clamp(cx, loX, hiX) - cx, ny = std::clamp(cy, loY, hiY) - cy;
    return nx * nx + ny * ny > inner * inner;
  }
  for (int k = 0; k < 4; ++k) {
    const float a = r.texel[0][k], b = r.texel[1][k], c = r.texel[2][k];
    if (c + std::min(a * loX, a * hiX) + std::min(b * loY, b * hiY) < 0.0f) return false;
  }
  return true;
}

// A bound on how thick the shape is: no square wider than this fits in it. An annulus's ring is
// as thick as its outer minus its inner radius (a disc: its diameter). A convex shape with two
// edges of exactly opposite normals (a line's sides and ends, ShapeSink::line: the normals are
// negated, which is exact) lies between them, d_0 + d_2 = c_0 + c_2 apart at every point; other
// shapes give no bound. A tile is only covered by a shape thicker than its samples' box is wide.
float TileBins::thickness(size_t shape) const {
  const ShapeRecord& r = shapes_[shape];
  if (r.texel[3][1] == kAnnulusKind) {
    const float outer = r.texel[0][2], inner = r.texel[0][3];
    return inner > 0.0f ? outer - inner : 2.0f * outer;
  }
  float thick = std::numeric_limits<float>::infinity();
  for (int k = 0; k < 2; ++k) {
    if (r.texel[0][k] == -r.texel[0][k + 2] && r.texel[1][k] == -r.texel[1][k + 2] &&
        (r.texel[0][k] != 0.0f || r.texel[1][k] != 0.0f)) {
      thick = std::min(thick, r.texel[2][k] + r.texel[2][k + 2]);
    }
  }
  return thick;
}

bool TileBins::reachesTile(size_t shape, int tx, int ty) const {
  const ShapeRecord& r = shapes_[shape];
  // The pixel centres of the tile span [lo, hi] on each axis.
  const float loX = float(tx * kTileSizePx) + 0.5f, hiX = float(std::min((tx + 1) * kTileSizePx, width_)) - 0.5f;
  const float loY = float(ty * kTileSizePx) + 0.5f, hiY = float(std::min((ty + 1) * kTileSizePx, height_)) - 0.5f;
  if (r.texel[3][1] == kAnnulusKind) {  // some centre within the grown ring
    const float cx = r.texel[0][0], cy = r.texel[0][1];
    const float nx = std::clamp(cx, loX, hiX) - cx, ny = std::clamp(cy, loY, hiY) - cy;
    const float fx = std::max(std::abs(loX - cx), std::abs(hiX - cx));
    const float fy = std::max(std::abs(loY - cy), std::abs(hiY - cy));
    const float outer = r.texel[0][2] + kFringePx, inner = r.texel[0][3] - kFringePx;
    if (nx * nx + ny * ny > outer * outer) return false;
    return !(inner > 0.0f && fx * fx + fy * fy < inner * inner);
  }
  const unsigned smooth = unsigned(r.texel[3][1]);
  for (int k = 0; k < 4; ++k) {
    const float a = r.texel[0][k], b = r.texel[1][k], c = r.texel[2][k];
    const float most = c + std::max(a * loX, a * hiX) + std::max(b * loY, b * hiY);
    const float push = (smooth >> k & 1u) ? kFringePx : 0.0f;
    if (most < -push - 1e-3f) return false;
  }
  return true;
}

template <typename Visit>
void TileBins::forEachReachedTile(std::uint32_t shape, int rowBegin, int rowEnd, Visit&& visit) const {
  const Reach& q = reach_[shape];
  // The test depends on the whole reach, not on the rows asked for: the same tiles in every band.
  const bool test = (q.tx1 - q.tx0 + 1) * (q.ty1 - q.ty0 + 1) > kTestedReach;
  const int last = std::min(q.ty1, rowEnd - 1);
  for (int ty = std::max(q.ty0, rowBegin); ty <= last; ++ty) {
    for (int tx = q.tx0; tx <= q.tx1; ++tx) {
      if (test && !reachesTile(shape, tx, ty)) continue;
      visit(size_t(ty) * size_t(tilesX_) + size_t(tx));
    }
  }
}

namespace {

// Tile rows per band of bin()'s work: 8 rows of 4 px tiles are 32 px, 23 bands in a 720 px frame,
// enough to share out over many threads, few enough that a shape rarely straddles two.
constexpr int kBandTileRows = 8;
// See bin(): a shape thinner than this cannot cover a whole tile.
constexpr float kThinnerThanTilesPx = float(kTileSizePx) - 0.5f;
// Shapes per chunk of bin()'s first passes (which band each shape goes to).
constexpr size_t kBinChunk = 16384;

}  // namespace

void TileBins::bin(WorkerPool* pool) {
  // A counting sort by tile, stable (each tile's shapes stay in the order they were added), done
  // band by band. First the shapes are sorted by band of tile rows (a shape in each band its rows
  // meet), by chunks of shapes counting then placing, so each band's list keeps the shapes' order.
  // Then each band, on its own, counts its tiles' shapes, and after one prefix sum over all tiles
  // places them: two passes over the shapes' tiles, the second repeating only the tile tests of
  // shapes reaching more than kTestedReach tiles, which are few. (One pass that kept (tile, shape)
  // pairs to sort took 8 bytes a pair, a vector of 134 to 268 MB for a million-particle cloth's
  // frames.) Every band and chunk writes only its own counts, lists and tiles: the
  // result is the same for every thread count, and the same as one serial counting sort.
  if (reach_.size() > size_t(UINT32_MAX)) throw std::length_error("TileBins: more shapes than a tile list can number");
  const size_t bands = size_t((tilesY_ + kBandTileRows - 1) / kBandTileRows);
  sortIntoBands(pool, bands);
  fillTiles(pool, bands);
  collectRuns();
}

void TileBins::sortIntoBands(WorkerPool* pool, size_t bands) {
  const size_t shapeCount = reach_.size();
  const size_t chunks = chunkCount(shapeCount, kBinChunk);
  auto eachBandOf = [&](const Reach& q, auto&& visit) {
    if (q.tx1 < q.tx0 || q.ty1 < q.ty0) return;
    for (int b = q.ty0 / kBandTileRows; b <= q.ty1 / kBandTileRows; ++b) visit(size_t(b));
  };

  chunkBandCounts_.resize(chunks * bands);
  forChunks(pool, shapeCount, kBinChunk, [&](size_t begin, size_t end) {
    std::uint32_t* count = &chunkBandCounts_[begin / kBinChunk * bands];
    std::fill(count, count + bands, 0u);
    for (size_t s = begin; s < end; ++s) eachBandOf(reach_[s], [&](size_t b) { ++count[b]; });
  });
  // Band b's list starts after every earlier band's; within it, chunk c's shapes after earlier chunks'.
  bandFirst_.assign(bands + 1, 0);
  for (size_t b = 0; b < bands; ++b) {
    size_t next = bandFirst_[b];
    for (size_t c = 0; c < chunks; ++c) {
      const std::uint32_t count = chunkBandCounts_[c * bands + b];
      chunkBandCounts_[c * bands + b] = std::uint32_t(next - bandFirst_[b]);
      next += count;
    }
    bandFirst_[b + 1] = next;
  }
  bandShapes_.resize(bandFirst_[bands]);
  forChunks(pool, shapeCount, kBinChunk, [&](size_t begin, size_t end) {
    std::uint32_t* next = &chunkBandCounts_[begin / kBinChunk * bands];
    for (size_t s = begin; s < end; ++s) {
      eachBandOf(reach_[s], [&](size_t b) { bandShapes_[bandFirst_[b] + next[b]++] = std::uint32_t(s); });
    }
  });
}

void TileBins::fillTiles(WorkerPool* pool, size_t bands) {
  const size_t tileCount = size_t(tilesX_) * size_t(tilesY_);
  auto bandRows = [&](size_t b) {
    const int first = int(b) * kBandTileRows;
    return std::pair<int, int>{first, std::min(first + kBandTileRows, tilesY_)};
  };
  tiles_.resize(2 * tileCount);
  forChunks(pool, bands, 1, [&](size_t b, size_t) {  // one band a task
    const auto [rowBegin, rowEnd] = bandRows(b);
    for (size_t t = size_t(rowBegin) * size_t(tilesX_); t < size_t(rowEnd) * size_t(tilesX_); ++t) tiles_[2 * t + 1] = 0;
    for (size_t i = bandFirst_[b]; i < bandFirst_[b + 1]; ++i) {
      forEachReachedTile(bandShapes_[i], rowBegin, rowEnd, [&](size_t tile) { ++tiles_[2 * tile + 1]; });
    }
  });
  std::uint32_t first = 0;
  for (size_t t = 0; t < tileCount; ++t) {
    tiles_[2 * t] = first;
    first += tiles_[2 * t + 1];
  }
  items_.resize(first);
  coverFrom_.resize(tileCount);
  // The tiles of kTileSizePx whole pixels each way (the rest: the last row or column, when the
  // image's side is not a multiple of the tile size). A whole tile's samples span a square wider
  // than kTileSizePx − 1 + 2 · ½ px (coversTile), so a shape thinner than kThinnerThanTilesPx (half a
  // pixel below that, far beyond float rounding) cannot cover it.
  const int wholeTilesX = width_ / kTileSizePx, wholeTilesY = height_ / kTileSizePx;
  forChunks(pool, bands, 1, [&](size_t b, size_t) {  // one band a task
    const auto [rowBegin, rowEnd] = bandRows(b);
    const size_t tileBegin = size_t(rowBegin) * size_t(tilesX_), tileEnd = size_t(rowEnd) * size_t(tilesX_);
    // Each tile's next free place in items_, in its count's entry (back to the count below), and
    // where its list will start: at the last shape covering the whole tile, if one does. Nothing
    // behind it shows there (the pass would stop at it or before, from the front; this spares it
    // the walk). The cover is tested as each shape is placed, while its record is in the cache.
    for (size_t t = tileBegin; t < tileEnd; ++t) {
      tiles_[2 * t + 1] = tiles_[2 * t];
      coverFrom_[t] = tiles_[2 * t];
    }
    for (size_t i = bandFirst_[b]; i < bandFirst_[b + 1]; ++i) {
      const std::uint32_t shape = bandShapes_[i];
      // Thinner than a whole tile: it can only cover the partial tiles of the last row or column.
      const bool thin = thickness(shape) < kThinnerThanTilesPx;
      forEachReachedTile(shape, rowBegin, rowEnd, [&](size_t tile) {
        const std::uint32_t place = tiles_[2 * tile + 1]++;
        items_[place] = shape;
        const int tx = int(tile % size_t(tilesX_)), ty = int(tile / size_t(tilesX_));
        if (thin && tx < wholeTilesX && ty < wholeTilesY) return;
        if (coversTile(shape, tx, ty)) coverFrom_[tile] = place;
      });
    }
    for (size_t t = tileBegin; t < tileEnd; ++t) {
      std::uint32_t* range = &tiles_[2 * t];
      range[1] = range[1] - coverFrom_[t];  // from the next free place to the count left
      range[0] = coverFrom_[t];
    }
  });
}

void TileBins::collectRuns() {
  runs_.clear();
  for (int ty = 0; ty < tilesY_; ++ty) {
    for (int tx = 0; tx < tilesX_;) {
      if (tiles_[2 * size_t(ty * tilesX_ + tx) + 1] == 0) {
        ++tx;
        continue;
      }
      const int start = tx;
      while (tx < tilesX_ && tiles_[2 * size_t(ty * tilesX_ + tx) + 1] != 0) ++tx;
      const float x0 = float(start * kTileSizePx), x1 = float(std::min(tx * kTileSizePx, width_));
      const float y0 = float(ty * kTileSizePx), y1 = float(std::min((ty + 1) * kTileSizePx, height_));
      runs_.insert(runs_.end(), {x0, y0, x1, y0, x1, y1, x0, y0, x1, y1, x0, y1});
    }
  }
}

}  // namespace particles::render
