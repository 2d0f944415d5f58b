#include "render/image_compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace particles::render {

namespace {

// The largest channel difference of pixel (x, y).
int pixelDifference(const Image& a, const Image& b, int x, int y) {
  const std::uint8_t* p = a.pixel(x, y);
  const std::uint8_t* q = b.pixel(x, y);
  int largest = 0;
  for (int c = 0; c < 4; ++c) largest = std::max(largest, std::abs(int(p[c]) - int(q[c])));
  return largest;
}

void requireSameSize(const Image& expected, const Image& actual) {
  const std::string mismatch = sizeMismatch(expected, actual);
  if (!mismatch.empty()) throw std::invalid_argument(mismatch);
}

void setRgb(std::uint8_t* px, const std::uint8_t (&rgb)[3]) {
  px[0] = rgb[0];
  px[1] = rgb[1];
  px[2] = rgb[2];
  px[3] = 255;
}

}  // namespace

std::string sizeMismatch(const Image& expected, const Image& actual) {
  return sizeMismatch(expected.width, expected.height, actual.width, actual.height);
}

std::string sizeMismatch(int expectedWidth, int expectedHeight, int actualWidth, int actualHeight) {
  if (expectedWidth == actualWidth && expectedHeight == actualHeight) return {};
  return fmt::format("sizes differ: {}×{} expected, {}×{} actual", expectedWidth, expectedHeight, actualWidth,
                     actualHeight);
}

ImageComparison compareImages(const Image& expected, const Image& actual, const CompareTolerance& tolerance) {
  requireSameSize(expected, actual);
  if (tolerance.threshold < 0 || tolerance.threshold > 255) {
    throw std::invalid_argument(fmt::format("threshold must be 0 … 255, not {}", tolerance.threshold));
  }
  if (!(tolerance.maxShare >= 0 && tolerance.maxShare <= 1)) {
    throw std::invalid_argument(fmt::format("the largest share must be 0 … 1, not {}", tolerance.maxShare));
  }
  ImageComparison r;
  r.width = expected.width;
  r.height = expected.height;
  r.pixels = long(expected.width) * long(expected.height);
  PixelBox box{expected.width, expected.height, -1, -1};
  for (int y = 0; y < expected.height; ++y) {
    for (int x = 0; x < expected.width; ++x) {
      const int d = pixelDifference(expected, actual, x, y);
      r.largestDifference = std::max(r.largestDifference, d);
      if (d <= tolerance.threshold) continue;
      ++r.differing;
      box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x), std::max(box.y1, y)};
    }
  }
  if (r.differing > 0) r.box = box;
  r.share = r.pixels > 0 ? double(r.differing) / double(r.pixels) : 0.0;
  r.passed = r.share <= tolerance.maxShare;
  return r;
}

Image diffImage(const Image& expected, const Image& actual, int threshold) {
  requireSameSize(expected, actual);
  Image out(expected.width, expected.height);
  std::optional<PixelBox> box;
  for (int y = 0; y < expected.height; ++y) {
    for (int x = 0; x < expected.width; ++x) {
      std::uint8_t* o = out.pixel(x, y);
      const int d = pixelDifference(expected, actual, x, y);
      if (d > threshold) {
        setRgb(o, kDiffHighlight);
        box = box ? PixelBox{std::min(box->x0, x), std::min(box->y0, y), std::max(box->x1, x), std::max(box->y1, y)}
                  : PixelBox{x, y, x, y};
      } else if (d > 0) {
        setRgb(o, kDiffNearMiss);
      } else {
        // Rec. 601 luma of the expected pixel, dimmed so that the highlights stand out.
        const std::uint8_t* e = expected.pixel(x, y);
        const double luma = 0.299 * e[0] + 0.587 * e[1] + 0.114 * e[2];
        const auto grey = std::uint8_t(std::lround(kDiffDim * luma));
        o[0] = o[1] = o[2] = grey;
        o[3] = 255;
      }
    }
  }
  if (box) {
    // The outline runs one pixel outside the box (clipped to the image) and never covers a
    // highlighted pixel, so a single differing pixel shows as a dot in a small square.
    const int x0 = std::max(box->x0 - 1, 0), x1 = std::min(box->x1 + 1, out.width - 1);
    const int y0 = std::max(box->y0 - 1, 0), y1 = std::min(box->y1 + 1, out.height - 1);
    auto outline = [&](int x, int y) {
      if (pixelDifference(expected, actual, x, y) <= threshold) setRgb(out.pixel(x, y), kDiffBox);
    };
    for (int x = x0; x <= x1; ++x) {
      outline(x, y0);
      outline(x, y1);
    }
    for (int y = y0; y <= y1; ++y) {
      outline(x0, y);
      outline(x1, y);
    }
  }
  return out;
}

}  // namespace particles::render
