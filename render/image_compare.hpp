#pragma once
// Comparing a rendered frame with its golden frame (docs/physics.md §10), and the picture that shows where
// they differ. Pure functions on Images: no files, no GL. `particles compare` and the golden-frame
// tests (golden/README.md) are built on them.
//
// A pixel differs when any of its channels (R, G, B, A) differs by more than `threshold`; the
// frames match when the share of differing pixels is at most `maxShare`. Both defaults come from
// measurement, see kDefaultThreshold and kDefaultMaxShare below and golden/README.md.

#include <optional>
#include <string>

#include "render/image.hpp"

namespace particles::render {

// The defaults, from measurement (golden/README.md has the tables, scripts/measure-golden measures
// them). Noise: every golden frame was byte-identical over repeated runs, LP_NUM_THREADS = 0, 1, 2,
// 8 and llvmpipe's default, LP_NATIVE_VECTOR_WIDTH = 128 and 256, and -O0, -O2 and
// -march=x86-64-v3 builds (largest difference 0). Signal: the renderer's fragment shader tests each
// pixel at 4 sample positions and blends the covered share, so a moved edge changes a pixel by
// whole quarters of the contrast across it: 54 … 255 in 127 of the 130 perturbed frames that
// changed a pixel (16 … 27 in the other three: a spring's colour follows its strain, and an edge
// over a spring has less contrast); one time step later changed ≥ 105 pixels (0.14 %) of every
// frame, one spring stiffness +5 % ≥ 46 pixels (0.06 %).
//
// Per channel, 0 … 255: a margin for rounding in blending the covered share on another Mesa or CPU
// (not measurable here, with one Mesa), under the quarter of the contrast a moved particle edge
// makes on the dark background (54).
inline constexpr int kDefaultThreshold = 16;
// Share of the pixels, 0 … 1: 0.02 % is 15 pixels of a 320×240 frame: room for a few pixels whose
// coverage changes with rounding-level differences in the simulation (the rigid chain is chaotic),
// and 3× under the weakest perturbation the golden tests must catch (ks +5 %: 46 pixels).
inline constexpr double kDefaultMaxShare = 0.0002;

struct CompareTolerance {
  int threshold = kDefaultThreshold;   // per channel, 0 … 255
  double maxShare = kDefaultMaxShare;  // 0 … 1
};

// Pixel rectangle [x0, x1] × [y0, y1], inclusive, top-left origin.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0 + 1; }
  int height() const { return y1 - y0 + 1; }
  bool operator==(const PixelBox&) const = default;
};

struct ImageComparison {
  int width = 0, height = 0;
  long differing = 0;           // pixels with a channel difference > threshold
  long pixels = 0;              // width · height
  double share = 0;             // differing / pixels (0 for an empty image)
  int largestDifference = 0;    // over every channel of every pixel, 0 … 255, whatever the threshold
  std::optional<PixelBox> box;  // bounding box of the differing pixels; none when nothing differs
  bool passed = true;           // share ≤ maxShare
};

// Throws std::invalid_argument when the sizes differ (the message names both, expected first) or a
// tolerance is out of range.
ImageComparison compareImages(const Image& expected, const Image& actual, const CompareTolerance& tolerance = {});

// "320×240 expected, 640×480 actual" style message for a size mismatch; empty when the sizes match.
std::string sizeMismatch(const Image& expected, const Image& actual);
// The same from the sizes alone (a PNG's header, render/png_io.hpp's readPngSize).
std::string sizeMismatch(int expectedWidth, int expectedHeight, int actualWidth, int actualHeight);

// Colours of the diff picture.
inline constexpr std::uint8_t kDiffHighlight[3] = {255, 0, 255};  // above the threshold: magenta, in no theme
inline constexpr std::uint8_t kDiffNearMiss[3] = {0, 150, 170};   // differs, but within the threshold
inline constexpr std::uint8_t kDiffBox[3] = {255, 220, 0};        // outline of the bounding box
inline constexpr double kDiffDim = 0.35;                          // the expected frame, grey, at this brightness

// The expected frame in grey at kDiffDim brightness; pixels that differ by more than `threshold`
// in kDiffHighlight, those that differ by less in kDiffNearMiss, and the bounding box of the
// differing pixels outlined in kDiffBox (on pixels that do not differ, one pixel outside the box
// where there is room). Opaque. Throws std::invalid_argument when the sizes differ.
Image diffImage(const Image& expected, const Image& actual, int threshold = kDefaultThreshold);

}  // namespace particles::render
