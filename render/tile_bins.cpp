#include "render/tile_bins.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace particles::render {

namespace {

float colorCode(Rgb col) {
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

void TileBins::reserve(size_t shapes) {
  shapes_.reserve(shapes);
  reach_.reserve(shapes);
}

void TileBins::clear() {
  shapes_.clear();
  reach_.clear();
}

// A pixel gets a shape's colour only if its centre lies in the shape grown by kFringePx (the
// triangle path's rule), so the box of the grown shape bounds its tiles; a box wholly off the
// image adds nothing (its shape still has a record, never listed).
void TileBins::addReach(float x0, float y0, float x1, float y1) {
  if (!(x1 >= 0.0f && y1 >= 0.0f && x0 <= float(width_) && y0 <= float(height_))) {
    reach_.push_back({0, 0, -1, -1});
    return;
  }
  reach_.push_back({clampTile(x0, tilesX_), clampTile(y0, tilesY_), clampTile(x1, tilesX_), clampTile(y1, tilesY_)});
}

void TileBins::convex(std::span<const P2> corners, Rgb col, unsigned smoothEdges) {
  const ConvexEdges e = convexEdges(corners, smoothEdges);
  if (!e.valid) return;
  ShapeRecord r{};
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
  r.texel[3][1] = float(smoothEdges & ((1u << e.count) - 1u));
  shapes_.push_back(r);
  float x0 = e.grown[0][0], x1 = x0, y0 = e.grown[0][1], y1 = y0;
  for (size_t i = 1; i < e.count; ++i) {
    x0 = std::min(x0, e.grown[i][0]), x1 = std::max(x1, e.grown[i][0]);
    y0 = std::min(y0, e.grown[i][1]), y1 = std::max(y1, e.grown[i][1]);
  }
  addReach(x0, y0, x1, y1);
}

// The rectangle ShapeSink::line makes, corners a + n, b + n, b − n, a − n, every edge smoothed.
void TileBins::line(P2 a, P2 b, float width, Rgb col, bool squareCaps) {
  float dx = b[0] - a[0], dy = b[1] - a[1];
  const float len = std::sqrt(dx * dx + dy * dy);
  if (!(len > 1e-4f)) return;
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
  ShapeRecord r{};
  for (int k = 0; k < 4; ++k) {
    r.texel[0][k] = inward[k][0];
    r.texel[1][k] = inward[k][1];
    r.texel[2][k] = -(inward[k][0] * corner[k][0] + inward[k][1] * corner[k][1]);
  }
  r.texel[3][0] = colorCode(col);
  r.texel[3][1] = 15.0f;
  shapes_.push_back(r);
  // The grown rectangle's corners lie within kFringePx·√2 of the rectangle's.
  const float grow = 1.5f * kFringePx;
  addReach(std::min({corner[0][0], corner[1][0], corner[2][0], corner[3][0]}) - grow,
           std::min({corner[0][1], corner[1][1], corner[2][1], corner[3][1]}) - grow,
           std::max({corner[0][0], corner[1][0], corner[2][0], corner[3][0]}) + grow,
           std::max({corner[0][1], corner[1][1], corner[2][1], corner[3][1]}) + grow);
}

void TileBins::annulus(P2 c, float inner, float outer, Rgb col) {
  ShapeRecord r{};
  r.texel[0][0] = c[0];
  r.texel[0][1] = c[1];
  r.texel[0][2] = outer;
  r.texel[0][3] = inner;
  r.texel[3][0] = colorCode(col);
  r.texel[3][1] = kAnnulusKind;
  shapes_.push_back(r);
  const float reach = outer + kFringePx;
  addReach(c[0] - reach, c[1] - reach, c[0] + reach, c[1] + reach);
}

// Whether the shape covers every sample of every pixel of the tile: samples lie within ±0.5 px of
// their pixel's centre (samplePattern), so it must contain the tile grown by half a pixel. Corners
// suffice for a convex shape; an annulus needs the farthest corner inside its outer circle and the
// nearest point outside its inner one.
bool TileBins::coversTile(size_t shape, int tx, int ty) const {
  const ShapeRecord& r = shapes_[shape];
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
void TileBins::forEachReachedTile(Visit&& visit) const {
  for (size_t s = 0; s < reach_.size(); ++s) {
    const Reach& q = reach_[s];
    const bool test = (q.tx1 - q.tx0 + 1) * (q.ty1 - q.ty0 + 1) > kTestedReach;
    for (int ty = q.ty0; ty <= q.ty1; ++ty) {
      for (int tx = q.tx0; tx <= q.tx1; ++tx) {
        if (test && !reachesTile(s, tx, ty)) continue;
        visit(size_t(ty * tilesX_ + tx), std::uint32_t(s));
      }
    }
  }
}

void TileBins::bin() {
  // A counting sort by tile, stable (each tile's shapes stay in the order they were added), in
  // two passes over the shapes' tiles: the first counts, the second places. One pass that kept
  // (tile, shape) pairs to sort took 8 bytes a pair, a vector of 134 to 268 MB for a
  // million-particle cloth's frames (issue 28); the second pass repeats only the tile tests of
  // shapes reaching more than kTestedReach tiles, which are few.
  const size_t tileCount = size_t(tilesX_) * size_t(tilesY_);
  tiles_.assign(2 * tileCount, 0);
  forEachReachedTile([&](size_t tile, std::uint32_t) { ++tiles_[2 * tile + 1]; });
  std::uint32_t first = 0;
  for (size_t t = 0; t < tileCount; ++t) {
    tiles_[2 * t] = first;
    first += tiles_[2 * t + 1];
  }
  items_.resize(first);
  std::vector<std::uint32_t>& next = scratch_;
  next.resize(tileCount);
  for (size_t t = 0; t < tileCount; ++t) next[t] = tiles_[2 * t];
  forEachReachedTile([&](size_t tile, std::uint32_t shape) { items_[next[tile]++] = shape; });

  // Nothing behind the last shape covering a whole tile shows there: the tile's list starts at it.
  // (The pass would stop at it or before, from the front; this spares it the walk.)
  for (int ty = 0; ty < tilesY_; ++ty) {
    for (int tx = 0; tx < tilesX_; ++tx) {
      std::uint32_t* range = &tiles_[2 * size_t(ty * tilesX_ + tx)];
      for (std::uint32_t i = range[1]; i-- > 1;) {
        if (coversTile(items_[range[0] + i], tx, ty)) {
          range[0] += i;
          range[1] -= i;
          break;
        }
      }
    }
  }

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
