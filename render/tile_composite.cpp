#include "render/tile_composite.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "render/shader_program.hpp"  // samplePattern

namespace particles::render {

namespace {

// One row of a tile's pixels: four floats, or four lanes' truth (−1 true, 0 false). GCC's and
// Clang's vector types, which compile to SSE2 on x86-64's baseline and to what another target has.
static_assert(kTileSizePx == 4, "a tile's row of pixels is one vector of four lanes");
using Row = float __attribute__((vector_size(16)));
using RowMask = std::int32_t __attribute__((vector_size(16)));
using RowWord = std::uint32_t __attribute__((vector_size(16)));  // four pixels' RGBA bytes
constexpr int kRows = kTileSizePx;

// Tile rows per task: 4 rows of 4 px tiles are 16 px, 45 tasks in a 720 px frame, where the shapes
// often gather in a few bands.
constexpr size_t kTaskTileRows = 4;
// How far down a tile's list the next records are fetched while one is composited.
constexpr std::uint32_t kPrefetchAhead = 4;

Row splat(float v) {
  return Row{v, v, v, v};
}

Row loadRow(const float (&v)[4]) {
  Row row;
  std::memcpy(&row, v, sizeof row);
  return row;
}

void storeRow(Row row, float (&v)[4]) {
  std::memcpy(v, &row, sizeof row);
}

// The next float above each finite lane of t (std::nextafter(t, ∞) without a call into libm or a
// branch): the bits one up for a positive lane, one down for a negative one, the least subnormal
// (bits 1) for ±0.
Row nextUp(Row t) {
  const RowWord bits = std::bit_cast<RowWord>(t);
  const RowWord moved = t > 0.0f ? bits + 1u : bits - 1u;
  return std::bit_cast<Row>(t == 0.0f ? RowWord{1u, 1u, 1u, 1u} : moved);
}

// Whether any of the four lanes is true.
bool anyLane(RowMask m) {
  return (m[0] | m[1] | m[2] | m[3]) != 0;
}

Row lesser(Row a, Row b) {
  return a < b ? a : b;
}

// The sample pattern's offsets, as floats (the shader's constants are floats too).
template <int S>
struct Offsets {
  float x[S], y[S];
};

// How many of each pixel's samples a convex shape covers, per row of the tile: the tile pass's
// coveredSamples (render/tile_program.cpp). A sample is inside edge k when d_k + o_k ≥ 0, o_k being
// the edge's offset at that sample, a_k·oₓ + b_k·o_y; rounding is monotonic and a nonzero sum of
// two floats is never rounded to 0, so that is exactly d_k ≥ −o_k, a comparison with a threshold
// made once per shape. A sample exactly on an edge (a tie, d_k = −o_k) is inside only when the edge
// is a top or left one, as GL's rasteriser decides a triangle's pixels (the triangle path's
// coverage comes from interpolated distances, whose rounding decides its ties; the GL tile pass
// counts every tie in): for any two shapes sharing an edge, exactly one has its samples on it. An
// edge that is not smoothed is decided at the pixel centre, by the same rule, for all its samples.
template <int S>
void convexCoverage(const ShapeRecord& r, Row x, float y0, const Offsets<S>& o, RowMask (&count)[kRows]) {
  // The four edges' thresholds side by side, edge k in lane k (one vector operation where there
  // were four of each, and no branch): the same float operations lane by lane.
  const Row a = loadRow(r.texel[0]), b = loadRow(r.texel[1]);
  const RowWord edgeBit = {1u, 2u, 4u, 8u};
  const RowMask tested = (RowWord(RowMask{} + int(r.texel[3][1])) & edgeBit) != 0u;
  const RowMask topOrLeft = (a > 0.0f) | ((a == 0.0f) & (b > 0.0f));  // inward normal right, or down (y down)
  // The least distance inside: the threshold itself, or the next float above it.
  const auto least = [&](Row threshold) { return topOrLeft ? threshold : nextUp(threshold); };
  const Row untested = splat(-std::numeric_limits<float>::infinity());
  float centreAt[4], sampleAt[S][4];
  storeRow(tested ? untested : least(splat(0.0f)), centreAt);
  for (int s = 0; s < S; ++s) storeRow(tested ? least(-(a * o.x[s] + b * o.y[s])) : untested, sampleAt[s]);
  Row cx[4];  // c + a·x: the distance's part that is the same in every row
  for (int k = 0; k < 4; ++k) cx[k] = splat(r.texel[2][k]) + splat(a[k]) * x;
  for (int row = 0; row < kRows; ++row) {
    const Row by = b * (y0 + float(row));
    Row d[4];
    for (int k = 0; k < 4; ++k) d[k] = cx[k] + splat(by[k]);
    const RowMask centreInside = (d[0] >= centreAt[0]) & (d[1] >= centreAt[1]) & (d[2] >= centreAt[2]) &
                                 (d[3] >= centreAt[3]);
    RowMask inside = RowMask{};
    for (int s = 0; s < S; ++s) {
      // A true lane is −1: one more covered sample.
      inside -= (d[0] >= sampleAt[s][0]) & (d[1] >= sampleAt[s][1]) & (d[2] >= sampleAt[s][2]) &
                (d[3] >= sampleAt[s][3]);
    }
    count[row] = inside & centreInside;
  }
}

// The same for an annulus (a disc when its inner radius is 0): a sample counts when its distance
// from the centre squared lies between the radii squared; a disc's inner test always holds.
template <int S, bool ring>
void annulusCoverage(const ShapeRecord& r, Row x, float y0, const Offsets<S>& o, RowMask (&count)[kRows]) {
  const float cx = r.texel[0][0], cy = r.texel[0][1];
  const float outer2 = r.texel[0][2] * r.texel[0][2], inner2 = r.texel[0][3] * r.texel[0][3];
  const Row qx = x - cx;
  Row px[S];
  for (int s = 0; s < S; ++s) px[s] = qx + o.x[s];
  for (int row = 0; row < kRows; ++row) {
    const float qy = y0 + float(row) - cy;
    RowMask inside = RowMask{};
    for (int s = 0; s < S; ++s) {
      const float py = qy + o.y[s];
      const Row r2 = px[s] * px[s] + py * py;
      if constexpr (ring) {
        inside -= (r2 <= outer2) & (r2 >= inner2);
      } else {
        inside -= r2 <= outer2;
      }
    }
    count[row] = inside;
  }
}

// Four pixels' bytes R, G, B, A from each channel's four values (the lanes, 0 … 255 whole numbers
// as floats): one pixel per 32-bit lane, R in its lowest byte, which is the first in memory on a
// little-endian machine.
static_assert(std::endian::native == std::endian::little, "pixels are packed as little-endian words");
void storePixels(const Row (&channel)[4], int columns, std::uint8_t* out) {
  RowWord word = RowWord{};
  for (int c = 0; c < 4; ++c) {
    const Row clamped = lesser(channel[c] < 0.0f ? splat(0.0f) : channel[c], splat(255.0f));
    word |= RowWord(__builtin_convertvector(clamped, RowMask)) << (8 * c);
  }
  std::memcpy(out, &word, size_t(columns) * 4);
}

// The tiles of tile rows [rowBegin, rowEnd) into the frame: those with shapes drawn, those without
// that held shapes before set to the background, the others left as they are.
template <int S>
void compositeRows(const TileBins& bins, const Offsets<S>& o, Rgb background, bool transparent, CompositedFrame& frame,
                   int rowBegin, int rowEnd) {
  Image& image = frame.image;
  const float backgroundAlpha = transparent ? 0.0f : 1.0f;
  const float back[3] = {float(background.r), float(background.g), float(background.b)};
  const Row cleared[4] = {splat(back[0] * backgroundAlpha), splat(back[1] * backgroundAlpha),
                          splat(back[2] * backgroundAlpha), splat(255.0f * backgroundAlpha)};
  const std::uint32_t* tiles = bins.tiles().data();
  const std::uint32_t* items = bins.items().data();
  const ShapeRecord* shapes = bins.shapes().data();
  for (int ty = rowBegin; ty < rowEnd; ++ty) {
    const int y0 = ty * kTileSizePx, rows = std::min(kTileSizePx, image.height - y0);
    for (int tx = 0; tx < bins.tilesPerRow(); ++tx) {
      const int x0 = tx * kTileSizePx, columns = std::min(kTileSizePx, image.width - x0);
      const size_t tile = size_t(ty) * size_t(bins.tilesPerRow()) + size_t(tx);
      const std::uint32_t first = tiles[2 * tile], listed = tiles[2 * tile + 1];
      const bool held = frame.tilesDrawn[tile] != 0;
      frame.tilesDrawn[tile] = listed != 0;
      if (listed == 0) {
        if (held) {
          for (int row = 0; row < rows; ++row) storePixels(cleared, columns, image.pixel(x0, y0 + row));
        }
        continue;
      }
      const float fx = float(x0) + 0.5f;
      const Row x = {fx, fx + 1.0f, fx + 2.0f, fx + 3.0f};
      const float fy = float(y0) + 0.5f;
      Row color[kRows][3] = {}, transmitted[kRows];
      for (Row& t : transmitted) t = splat(1.0f);
      // Front to back (the list runs back to front), until every pixel is covered whole.
      for (std::uint32_t i = listed; i-- > 0;) {
        if (i >= kPrefetchAhead) __builtin_prefetch(&shapes[items[first + i - kPrefetchAhead]]);
        const ShapeRecord& r = shapes[items[first + i]];
        RowMask count[kRows];
        if (r.texel[3][1] == kAnnulusKind) {
          if (r.texel[0][3] != 0.0f) {
            annulusCoverage<S, true>(r, x, fy, o, count);
          } else {
            annulusCoverage<S, false>(r, x, fy, o, count);
          }
        } else {
          convexCoverage<S>(r, x, fy, o, count);
        }
        // A shape listed here that covers none of the tile's samples (a thin spring's box reaches
        // tiles it misses; a 0.1 px particle covers a sample now and then) changes nothing: every
        // share below would be +0 and every transmitted factor 1.
        if (!anyLane(count[0] | count[1] | count[2] | count[3])) continue;
        const auto code = std::uint32_t(r.texel[3][0]);
        const float shapeColor[3] = {float(code & 0xFFu), float(code >> 8 & 0xFFu), float(code >> 16 & 0xFFu)};
        const float shapeAlpha = r.texel[3][2];  // 0 … 255
        RowMask showing = RowMask{};
        for (int row = 0; row < kRows; ++row) {
          // The covered share times the shape's alpha, rounded to 8 bits, as the shader's
          // floor(n · alpha / S + 0.5) / 255: n · alpha is a whole number below 2^13, exact.
          const Row n = __builtin_convertvector(count[row], Row);
          const Row alpha =
              __builtin_convertvector(__builtin_convertvector(n * shapeAlpha / float(S) + 0.5f, RowMask), Row) / 255.0f;
          const Row share = transmitted[row] * alpha;
          for (int c = 0; c < 3; ++c) color[row][c] += share * shapeColor[c];
          transmitted[row] *= 1.0f - alpha;
          showing |= transmitted[row] > 0.0f;
        }
        if (!anyLane(showing)) break;
      }
      for (int row = 0; row < rows; ++row) {
        // The shader's output, floor(colour + 0.5) / 255 and its alpha, as GL stores them in 8 bits.
        Row channel[4];
        const Row behind = transmitted[row] * backgroundAlpha;
        for (int c = 0; c < 3; ++c) channel[c] = color[row][c] + behind * back[c] + 0.5f;
        channel[3] = (1.0f - transmitted[row] * (1.0f - backgroundAlpha)) * 255.0f + 0.5f;
        storePixels(channel, columns, image.pixel(x0, y0 + row));
      }
    }
  }
}

template <int S>
void compositeAll(const TileBins& bins, Rgb background, bool transparent, CompositedFrame& frame, WorkerPool* pool) {
  Offsets<S> o;
  const auto& pattern = samplePattern(S);
  for (int s = 0; s < S; ++s) {
    o.x[s] = float(pattern[size_t(s)][0]);
    o.y[s] = float(pattern[size_t(s)][1]);
  }
  forChunks(pool, size_t(bins.tileRows()), kTaskTileRows, [&](size_t begin, size_t end) {
    compositeRows<S>(bins, o, background, transparent, frame, int(begin), int(end));
  });
}

}  // namespace

void compositeTiles(const TileBins& bins, int samples, Rgb background, bool transparent, CompositedFrame& frame,
                    WorkerPool* pool) {
  Image& image = frame.image;
  if (image.width != bins.width() || image.height != bins.height() ||
      image.rgba.size() != size_t(image.width) * size_t(image.height) * 4) {
    throw std::invalid_argument("compositeTiles: the image is " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + ", the tiles' frame " + std::to_string(bins.width()) +
                                "x" + std::to_string(bins.height()));
  }
  const size_t tileCount = size_t(bins.tilesPerRow()) * size_t(bins.tileRows());
  if (frame.tilesDrawn.size() != tileCount || frame.background != background || frame.transparent != transparent) {
    // Unknown content: every tile is rewritten, as if each had held shapes.
    frame.tilesDrawn.assign(tileCount, 1);
    frame.background = background;
    frame.transparent = transparent;
  }
  switch (samples) {
    case 1: return compositeAll<1>(bins, background, transparent, frame, pool);
    case 2: return compositeAll<2>(bins, background, transparent, frame, pool);
    case 4: return compositeAll<4>(bins, background, transparent, frame, pool);
    case 8: return compositeAll<8>(bins, background, transparent, frame, pool);
    case 16: return compositeAll<16>(bins, background, transparent, frame, pool);
    default:
      throw std::invalid_argument("compositeTiles: no sample pattern for " + std::to_string(samples) + " samples");
  }
}

}  // namespace particles::render
